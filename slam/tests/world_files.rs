//! World files found by fuzzing (`fuzz/fuzz_targets/world_file.rs`): a world that loads
//! writes itself back as text that loads as the same world.

use soar_slam::world::World;

fn round_trips(text: &str) {
    let world = World::from_toml_str(text).expect("the world loads");
    let again = World::from_toml_str(&world.to_toml_string()).expect("written back, it loads");
    assert_eq!(world, again, "written back, it is the same world");
}

#[test]
fn a_heading_whose_radians_do_not_convert_back_exactly_round_trips() {
    // 3° is 0.05235987755982989 rad, which converts back to 3.0000000000000004°.
    let text = "name = \"sroom\"\n\n[robot]\nx = 1.0\ny = 0.0\nheading = 3.0\n\n\
                [[wall]]\nx1 = -4.0\ny1 =3.0\nx2 = -4.0\ny2 = -3.0\n";
    round_trips(text);
}

#[test]
fn every_whole_and_tenth_degree_heading_round_trips() {
    for tenths in -3600..=3600 {
        let text = format!(
            "[robot]\nx = 0.0\ny = 0.0\nheading = {}\n\n[[wall]]\nx1 = 0\ny1 = 1\nx2 = 1\ny2 = 1\n",
            tenths as f64 / 10.0
        );
        round_trips(&text);
    }
}
