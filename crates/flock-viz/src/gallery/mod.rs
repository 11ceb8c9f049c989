//! The gallery page of `flocking figures` ([`index`]): each fixture's figures beside what its paper
//! says ([`papers`]) and its whole-run measures ([`whole_run`]).

pub mod index;
pub mod papers;
pub mod whole_run;
