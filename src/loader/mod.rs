//! Scene files → a description with typed quantities and source locations.
