//! Reproduction of the paper (work in progress).
