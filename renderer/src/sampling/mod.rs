//! Pure sampling routines.
