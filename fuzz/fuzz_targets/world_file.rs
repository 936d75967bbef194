//! World files for `rusoar slam`: any text either loads as a world or gives an error; a
//! world that loads writes itself back as text that loads as the same world.
#![no_main]

use libfuzzer_sys::fuzz_target;
use soar_slam::world::World;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if text.len() > rusoar_fuzz::MAX_INPUT {
        return;
    }
    if let Ok(world) = World::from_toml_str(text) {
        let again = World::from_toml_str(&world.to_toml_string())
            .expect("a world written back loads again");
        assert_eq!(world, again, "a world written back is the same world");
    }
});
