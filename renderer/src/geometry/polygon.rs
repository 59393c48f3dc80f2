//! Polygons.
