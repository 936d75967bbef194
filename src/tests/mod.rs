//! The kernel's tests of its parts, beyond the unit tests beside each module: the parser on
//! a corpus of files, printing and parsing rules back, and the matcher against a naive one.
//! (`tests/` holds the tests that use only the public API.)

mod parse_corpus;
mod rete_vs_naive;
mod roundtrip;
