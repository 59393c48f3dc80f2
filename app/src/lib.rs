//! The `lumis` application as a library: the interactive viewer, so that its UI tests
//! (`app/tests/`) can drive it; the binary (`main.rs`) adds the command line.
#![warn(missing_docs)]

pub mod viewer;
