//! Materials (BSDFs) evaluated per wavelength.
