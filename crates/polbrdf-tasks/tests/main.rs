//! Tests of the task layer: one module per job (added with the jobs).
