//! The `lumis` application as a library: the interactive viewer, so that its UI tests
//! (`app/tests/`) can drive it, and the part files of `render --sample-range` / `merge`, so that
//! tests can read their sums; the binary (`main.rs`) adds the command line.
#![warn(missing_docs)]

pub mod part_file;
pub mod scene_file;
pub mod viewer;
