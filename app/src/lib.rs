//! The `lumis` application as a library: the interactive viewer, so that its UI tests
//! (`app/tests/`) can drive it, the part files of `render --sample-range` / `merge`, so that
//! tests can read their sums, the loading of a command's scene file (its warnings and `-D`
//! parameters), the image size options, and which delta lights a BSDF-only render leaves out
//! (said by the commands and the viewer alike); the binary (`main.rs`) adds the command line.
#![warn(missing_docs)]

pub mod delta_lights;
pub mod image_size;
pub mod part_file;
pub mod scene_file;
pub mod viewer;
