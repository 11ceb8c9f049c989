//! Integration tests of flock-protocols: the theorems of TAC 2006 checked numerically.

mod common;
mod determinism;
mod invariance;
mod theory;
