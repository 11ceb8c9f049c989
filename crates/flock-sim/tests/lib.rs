//! Integration tests of flock-protocols: the theorems of TAC 2006 checked numerically.

mod algorithm3;
mod collisions;
mod common;
mod conditions;
mod determinism;
mod invariance;
mod local_form;
mod long_run;
mod model_examples;
mod models;
mod olfati_saber2003;
mod olfati_saber2003_tracking;
mod properties;
mod reynolds_reading;
mod split_step;
mod storage_order;
mod storage_order_models;
mod tanner2003;
mod theory;
