//! The lattice summary, the defect factor and the TAC 2006 Definition 5 verdict of a finished
//! `flock run` directory (2D), read from its `metrics.csv` and `final.csv`.
//!
//! `cargo run -p flock-metrics --example run_verdict -- DIR [d] [r] [a b]`
//!
//! d and r default to 7 and 1.2 d; the defect factor (of the 2003 potential, smooth adjacency with
//! flat part d/r) is printed when a and b (0 < a < b) are given.

use std::path::Path;

use flock_graph::ProximityNet;
use flock_math::Bump;
use flock_metrics::{
    DefectFactor, EDGE_TOLERANCE, FlockMetrics, FlockingCriteria, FlockingVerdict, LatticeSummary,
};
use glam::DVec2;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(dir) = args.first() else {
        return Err("usage: run_verdict DIR [d] [r] [a b]".into());
    };
    let number = |k: usize, default: f64| args.get(k).map_or(Ok(default), |s| s.parse::<f64>());
    let d = number(1, 7.0)?;
    let r = number(2, 1.2 * d)?;
    let dir = Path::new(dir);

    let (header, rows) = read_csv(&dir.join("metrics.csv"))?;
    let column = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .ok_or(format!("no column {name}"))
    };
    let [
        t,
        c,
        giant,
        radius,
        deviation,
        mismatch,
        min_distance,
        collisions,
    ] = [
        "t",
        "connectivity",
        "giant_component",
        "cohesion_radius",
        "deviation_energy",
        "velocity_mismatch",
        "min_distance",
        "collisions",
    ]
    .map(column);
    let (t, c, giant, radius, deviation, mismatch, min_distance, collisions) = (
        t?,
        c?,
        giant?,
        radius?,
        deviation?,
        mismatch?,
        min_distance?,
        collisions?,
    );
    let records: Vec<(f64, FlockMetrics)> = rows
        .iter()
        .map(|row| {
            (
                row[t],
                FlockMetrics {
                    connectivity: row[c],
                    giant_component: row[giant],
                    // metrics.csv has no component count: one component exactly when C = 1
                    // (C = (n − #components)/(n − 1)), "2" standing for "more than one"
                    components: if row[c] >= 1.0 { 1 } else { 2 },
                    cohesion_radius: row[radius],
                    deviation_energy: row[deviation],
                    velocity_mismatch: row[mismatch],
                    min_distance: row[min_distance],
                    collisions: row[collisions] as usize,
                },
            )
        })
        .collect();
    if let Some(verdict) = FlockingVerdict::judge(&records, &FlockingCriteria::default()) {
        println!("{verdict}");
    }

    let (_, agents) = read_csv(&dir.join("final.csv"))?;
    let q: Vec<DVec2> = agents
        .iter()
        .map(|row| DVec2::new(row[1], row[2]))
        .collect();
    let net = ProximityNet::brute_force(&q, r);
    println!("{}", LatticeSummary::measure(&q, &net, d, EDGE_TOLERANCE));
    if let (Some(a), Some(b)) = (args.get(3), args.get(4)) {
        let defect = DefectFactor::new(
            d,
            r,
            a.parse()?,
            b.parse()?,
            Some(Bump::influence_map(d / r, 1)),
        );
        let m = defect.measure(&q, &net);
        println!(
            "defect: μ = {:.4e} (V = {:.4e}, ‖∇V‖² = {:.4e}, w = {:.4}), μ_n = {:.4e} over {} edges",
            m.factor,
            m.potential,
            m.gradient_squared,
            defect.weight(),
            m.normalised,
            m.edges
        );
    }
    Ok(())
}

/// A CSV file: its header and its numeric rows.
type Table = (Vec<String>, Vec<Vec<f64>>);

/// Reads a CSV file of numbers.
fn read_csv(path: &Path) -> Result<Table, Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string(path)?;
    let mut lines = text.lines();
    let header = lines
        .next()
        .ok_or("empty file")?
        .split(',')
        .map(str::to_owned)
        .collect();
    let rows = lines
        .map(|line| line.split(',').map(str::parse).collect())
        .collect::<Result<_, _>>()?;
    Ok((header, rows))
}
