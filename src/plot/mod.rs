//! Headless PNG plots (in progress).
