//! `rusoar._rusoar`: the rusoar kernel for Python. `rusoar.sml` (Python) presents it as the
//! official kernel's `soar_sml` module: the same classes, methods, argument orders and
//! callback arguments; `rusoar` (Python) adds a Pythonic layer over the same classes.
//!
//! The agents live on a kernel thread ([`engine`]); the client keeps a copy of each agent's
//! input and output links ([`mirror`]), as an SML client does, so reading them and changing
//! the input-link cost no trip to that thread. [`slam`] is `rusoar slam` split into runs
//! that can be carried out anywhere, for `rusoar.sweep`'s Ray tasks.

mod agent;
mod dispatch;
mod engine;
mod errors;
mod kernel;
mod mirror;
mod shared;
mod slam;
mod sml_events;
mod wme;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _rusoar(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<kernel::Kernel>()?;
    m.add_class::<agent::Agent>()?;
    m.add_class::<wme::WMElement>()?;
    m.add_class::<wme::Identifier>()?;
    m.add_class::<wme::IntElement>()?;
    m.add_class::<wme::FloatElement>()?;
    m.add_class::<wme::StringElement>()?;
    m.add("SoarError", m.py().get_type::<errors::SoarError>())?;
    slam::register(m)?;
    Ok(())
}
