//! [`plot_run`] (`flocking plot DIR`, `flocking run --plot`): the figures of a finished run, with the
//! obstacles, the γ-agent, the desired distance and the Tanner law's fixed graph read back from the
//! run's resolved `scenario.ron`; [`plot_run_with`] with options (edges coloured by stress);
//! [`run_scene`] the same scene of frames held in memory.

use std::path::{Path, PathBuf};

use flock_math::Vector;
use flocking::build::gamma_agent;
use flocking::initial::to_vector;
use flocking::obstacles::{ObstacleSpec, Space};
use flocking::protocols::CollectiveState;
use flocking::{Scenario, VerdictKind};
use glam::{DMat2, DQuat, DVec2, DVec3};

use crate::{
    Drawable, FigureOptions, Frame, Output, ReynoldsOptions, RunData, Scene, View, VizError, lift,
    reynolds_png, reynolds_svg, write_figures,
};

/// Why figures could not be drawn.
#[derive(Debug)]
pub enum PlotError {
    /// The run's `scenario.ron` is missing or invalid.
    Scenario(flocking::ScenarioError),
    /// Reading the run's CSV files or drawing failed.
    Viz(VizError),
    /// The run directory is being written by another process (a run, a resume, another
    /// `plot`), or its lock could not be taken.
    Dir(flocking::owned::DirError),
    /// A snapshot time asked for is not within the run.
    Time {
        /// The time asked for (s).
        time: f64,
        /// The run's first and last recorded times (s).
        span: (f64, f64),
    },
}

impl PlotError {
    /// Whether the plot was refused as asked (exit code 2: an invalid scenario, a directory
    /// another process writes, a time outside the run, a file flocking never writes through or
    /// over) rather than failed while drawing (1).
    #[must_use]
    pub fn is_refusal(&self) -> bool {
        match self {
            Self::Scenario(_) | Self::Dir(_) | Self::Time { .. } => true,
            // `write_no_follow`'s refusals: a link, a user's file, a user's `NAME.tmp`
            Self::Viz(VizError::Io { source, .. }) => {
                source.kind() == std::io::ErrorKind::AlreadyExists
            }
            Self::Viz(_) => false,
        }
    }
}

impl std::fmt::Display for PlotError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Viz(e) => write!(f, "{e}"),
            Self::Dir(e) => write!(f, "{e}; plot it once that process is done"),
            Self::Time {
                time,
                span: (first, last),
            } => write!(
                f,
                "snapshot time {time} s is outside the run, which spans {first} s to {last} s; give times within it"
            ),
        }
    }
}

impl std::error::Error for PlotError {}

/// Draws the figures of the run in `dir` (snapshots, metric curves, GIF, HTML player; for a
/// `Flocking2003` run ACC 2004's reading of one frame as Reynolds's rules, `reynolds.svg/png`,
/// [`reynolds_svg`]) into `dir/figures/`, and returns the files written. A Tanner run is drawn on its fixed graph with
/// velocity arrows, as Tanner et al. draw Figs. 3–8. The metric panels are those of the run's
/// model ([`MetricsOptions::kind`](crate::MetricsOptions::kind)); the classic models are drawn
/// without edges, a 3D mill down its axis.
///
/// # Errors
/// When `dir` is not a complete run directory, or drawing fails.
pub fn plot_run(dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    plot_run_with(dir, &FigureOptions::default())
}

/// [`plot_run`] with `options` (the figures of `options.outputs`; a run on a fixed graph gets velocity arrows and dotted trails
/// from the start whatever they say;
/// the scenario's `snapshots` times, when it has them and `options` gives none).
///
/// # Errors
/// As [`plot_run`]; [`PlotError::Time`] for a time of `options.snapshot_times` outside the run.
pub fn plot_run_with(dir: &Path, options: &FigureOptions) -> Result<Vec<PathBuf>, PlotError> {
    let scenario = Scenario::load(dir.join("scenario.ron")).map_err(PlotError::Scenario)?;
    // one writer at a time: the figures and the manifest's record of them (issue 27)
    let _lock = flocking::owned::DirLock::acquire(dir).map_err(PlotError::Dir)?;
    let run = RunData::load(dir).map_err(PlotError::Viz)?;
    let scene = run_scene(&scenario, run.scene(scenario.range())).map_err(PlotError::Scenario)?;
    check_times(
        &scene,
        options.snapshot_times.as_deref().unwrap_or_default(),
    )?;
    let mut options = options.clone();
    if options.snapshot_times.is_none() {
        options.snapshot_times.clone_from(&scenario.snapshots);
    }
    let kind = VerdictKind::of(&scenario.algorithm);
    options.metrics.kind = kind;
    if !kind.has_lattice() {
        draw_as_collective_motion(&scene, &mut options);
    }
    if scene.interaction_graph.is_some() {
        // a run on a fixed graph (the Tanner law, Consensus), drawn as Tanner et al. 2003 Figs. 3–8:
        // velocity arrows and each trajectory dotted from the start
        options.snapshot.style.velocity_arrows = true;
        options.snapshot.style.trail = scene.frames.len();
        options.snapshot.style.dotted_trails = true;
    }
    let figures = dir.join("figures");
    let mut written =
        write_figures(&scene, Some(&run.metrics), &figures, &options).map_err(PlotError::Viz)?;
    if let Some(alpha) = scenario
        .alpha_alpha()
        .filter(|_| options.draws(Output::Snapshots))
    {
        let time = options
            .reynolds_time
            .unwrap_or_else(|| reynolds_time(&scenario, &scene));
        let frame = scene.frame_nearest(time).unwrap_or_default();
        let reynolds = ReynoldsOptions {
            view: options.snapshot.style.view,
            length_unit: options.snapshot.style.length_unit.clone(),
            ..ReynoldsOptions::default()
        };
        let mut write = |name: &str, bytes: &[u8]| {
            let path = figures.join(name);
            // never through a link, as write_figures
            flocking::owned::write_no_follow(&path, bytes).map_err(|source| {
                PlotError::Viz(VizError::Io {
                    path: path.clone(),
                    source,
                })
            })?;
            written.push(path);
            Ok::<_, PlotError>(())
        };
        if options.svg {
            let svg = reynolds_svg(&scene, frame, &alpha, &reynolds).map_err(PlotError::Viz)?;
            write("reynolds.svg", svg.as_bytes())?;
        }
        if options.png {
            let png = reynolds_png(&scene, frame, &alpha, &reynolds).map_err(PlotError::Viz)?;
            write("reynolds.png", &png)?;
        }
    }
    Ok(written)
}

/// Checks that `flocking plot DIR` (and Python's `flocking.plot`) may draw into `DIR/figures`:
/// `DIR` is a complete run directory, and its `figures` is flocking's (`DIR` carries flocking's
/// marker, and its manifest, when it has one, lists each figure present with its size and
/// content) or does not exist yet, so that no file flocking did not write is replaced.
///
/// # Errors
/// The message saying why not, and what to give instead.
pub fn check_plot_dir(dir: &Path) -> Result<(), String> {
    if !dir.is_dir() {
        return Err(format!(
            "{} is not a directory; give a run directory written by `flocking run` (with its scenario.ron and metrics.csv)",
            dir.display()
        ));
    }
    for name in ["scenario.ron", "metrics.csv"] {
        if !dir.join(name).is_file() {
            let partial = flocking::run_dir::partial_path(dir);
            let hint = if partial.is_dir() {
                format!(
                    "; the run is still in {} (finish it with `flocking run --resume {}`)",
                    partial.display(),
                    dir.display()
                )
            } else {
                String::new()
            };
            return Err(format!(
                "{} is not a complete run directory: it has no {name}{hint}",
                dir.display()
            ));
        }
    }
    let figures = dir.join(flocking::owned::FIGURES_DIR);
    let foreign = |entry: String| {
        Err(flocking::owned::DirError::Foreign {
            dir: dir.to_owned(),
            entry,
        }
        .to_string())
    };
    let Ok(meta) = std::fs::symlink_metadata(&figures) else {
        return Ok(());
    };
    if !flocking::owned::marked(dir, flocking::owned::Kind::Run) || !meta.is_dir() {
        // a link (to a user's directory), a file, or figures of a directory without the marker
        return foreign("figures".into());
    }
    // a figure's name that is a link or a directory is not one of flocking's files
    for name in flocking::owned::RUN_FIGURES {
        if std::fs::symlink_metadata(figures.join(name)).is_ok_and(|m| !m.is_file()) {
            return foreign(format!("figures/{name}"));
        }
    }
    // a figure the user saved over one of flocking's (issue 27: ownership by content)
    let figures: Vec<String> = flocking::owned::RUN_FIGURES
        .iter()
        .map(|name| format!("{}/{name}", flocking::owned::FIGURES_DIR))
        .collect();
    flocking::owned::check_files(dir, &figures).map_err(|e| e.to_string())
}

/// Refuses a snapshot time outside the recorded span of the run (or not a number).
fn check_times(scene: &Scene, times: &[f64]) -> Result<(), PlotError> {
    let (Some(first), Some(last)) = (scene.frames.first(), scene.frames.last()) else {
        return Ok(());
    };
    let span = (first.t, last.t);
    // a time written as the run's end (its duration) is the last record, up to rounding
    let slack = 1e-9 * span.1.abs().max(1.0);
    match times
        .iter()
        .find(|&&t| !(span.0 - slack..=span.1 + slack).contains(&t))
    {
        Some(&time) => Err(PlotError::Time { time, span }),
        None => Ok(()),
    }
}

/// How the models without an α-lattice (Vicsek, boids, Couzin, Cucker–Smale, Vásárhelyi) are
/// drawn: without the net's edges (every pair within their interaction range — Couzin's zone of
/// attraction, Vásárhelyi's r_c — would hide the agents under a grey blob), each marker along its
/// heading; in 3D, a group that mills at the last frame ([`mill_axis`]) is seen down its axis,
/// where the mill is a ring, instead of obliquely.
fn draw_as_collective_motion(scene: &Scene, options: &mut FigureOptions) {
    options.snapshot.style.edges = false;
    if scene.dim == 3
        && let Some(axis) = scene.frames.last().and_then(mill_axis)
    {
        options.snapshot.style.view = View::along(axis);
    }
}

/// The axis of a mill, (1/n) Σ_i r̂_ic × p̂_i of the frame (Couzin et al. 2002's m_group is its
/// length), when the frame mills: m_group ≥ Couzin's torus threshold 0.5
/// ([`CollectiveState::TORUS`]); `None` otherwise.
#[must_use]
pub fn mill_axis(frame: &Frame) -> Option<DVec3> {
    let n = frame.positions.len();
    if n < 2 {
        return None;
    }
    let centre = frame.positions.iter().sum::<DVec3>() / n as f64;
    let axis = frame
        .positions
        .iter()
        .zip(&frame.velocities)
        .map(|(&q, &p)| {
            (q - centre)
                .normalize_or_zero()
                .cross(p.normalize_or_zero())
        })
        .sum::<DVec3>()
        / n as f64;
    (axis.length() >= CollectiveState::TORUS).then_some(axis)
}

/// The default time of an (α, α) run's `reynolds.svg/png`: the second of the scenario's
/// `snapshots` (the first after the start, where the agents already move and the regimes are
/// still mixed), else a tenth of the run.
#[must_use]
pub fn reynolds_time(scenario: &Scenario, scene: &Scene) -> f64 {
    match scenario.snapshots.as_deref() {
        Some([_, second, ..]) => *second,
        _ => scene.frames.last().map_or(0.0, |f| 0.1 * f.t),
    }
}

/// The scene of a run of `scenario` whose frames `scene` holds: with its title, desired distance,
/// obstacles, γ-agent and (Tanner) fixed graph, as [`plot_run`] draws it (the Python package's
/// player of a run held in memory).
///
/// # Errors
/// A Tanner scenario whose fixed graph cannot be built.
pub fn run_scene(scenario: &Scenario, scene: Scene) -> Result<Scene, flocking::ScenarioError> {
    match scenario.dim {
        2 => decorate::<DVec2>(scene, scenario),
        _ => decorate::<DVec3>(scene, scenario),
    }
}

/// The scene with its title, desired distance, obstacles, periodic box, γ-agent and fixed graph
/// (Tanner, consensus on a fixed graph).
fn decorate<V: Space>(scene: Scene, scenario: &Scenario) -> Result<Scene, flocking::ScenarioError> {
    let mut scene = scene
        .with_title(scenario.name.clone())
        .with_desired_distance(scenario.alpha.d);
    if scenario.fixed_graph().is_some() {
        let graph = scenario.tanner_graph()?;
        scene = scene.with_interaction_graph(
            (0..graph.len()).flat_map(|i| graph.neighbours(i).iter().map(move |&j| (i as u32, j))),
        );
    }
    for spec in &scenario.obstacles {
        scene = scene.with_obstacle(drawable::<V>(spec));
    }
    if let Some(size) = scenario.box_size() {
        scene = scene.with_periodic_box(DVec3::from_fn(|k| size.get(k).copied().unwrap_or(0.0)));
    }
    Ok(match scenario.algorithm.gamma() {
        Some(gamma) => {
            let gamma = gamma_agent::<V>(gamma);
            scene.with_gamma(move |t| lift(gamma.state(t).0))
        }
        None => scene,
    })
}

/// How an obstacle is drawn (a validated spec of dimension `V::DIM`).
fn drawable<V: Vector>(spec: &ObstacleSpec) -> Drawable {
    let v = |x: &[f64]| to_vector::<V>(x);
    match spec {
        ObstacleSpec::Ball { centre, radius } => Drawable::ball(v(centre), *radius),
        ObstacleSpec::Wall { point, normal } => Drawable::half_space(v(point), v(normal)),
        ObstacleSpec::Cuboid {
            centre,
            half_extents,
            rotation,
        } => Drawable::convex_hull(&cuboid_corners::<V>(centre, half_extents, rotation)),
        ObstacleSpec::ConvexHull { points } => {
            Drawable::convex_hull(&points.iter().map(|p| v(p)).collect::<Vec<V>>())
        }
        ObstacleSpec::Capsule { a, b, radius } => Drawable::capsule(v(a), v(b), *radius),
        ObstacleSpec::Segment { a, b } => Drawable::capsule(v(a), v(b), 0.0),
        ObstacleSpec::Triangle { a, b, c } => Drawable::convex_hull(&[v(a), v(b), v(c)]),
    }
}

/// The 2^m corners of a rotated box (2D: angle; 3D: axis-angle vector).
fn cuboid_corners<V: Vector>(centre: &[f64], half: &[f64], rotation: &[f64]) -> Vec<V> {
    let corners = 1usize << V::DIM;
    (0..corners)
        .map(|mask| {
            let local: Vec<f64> = (0..V::DIM)
                .map(|k| {
                    if mask >> k & 1 == 1 {
                        half[k]
                    } else {
                        -half[k]
                    }
                })
                .collect();
            let turned = if V::DIM == 2 {
                let angle = rotation.first().copied().unwrap_or(0.0);
                DMat2::from_angle(angle)
                    .mul_vec2(DVec2::new(local[0], local[1]))
                    .extend(0.0)
            } else {
                let axis = DVec3::new(
                    rotation.first().copied().unwrap_or(0.0),
                    rotation.get(1).copied().unwrap_or(0.0),
                    rotation.get(2).copied().unwrap_or(0.0),
                );
                DQuat::from_scaled_axis(axis) * DVec3::new(local[0], local[1], local[2])
            };
            V::from_fn(|k| centre[k] + turned[k])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ring of agents circling the axis (1, 1, 1) is a mill seen down that axis; the same
    /// agents all heading one way mill not.
    #[test]
    fn a_mill_is_seen_down_its_axis() {
        let axis = DVec3::ONE.normalize();
        let (u, v) = (
            DVec3::new(1.0, -1.0, 0.0).normalize(),
            axis.cross(DVec3::new(1.0, -1.0, 0.0).normalize()),
        );
        let angles: Vec<f64> = (0..24)
            .map(|k| f64::from(k) * core::f64::consts::TAU / 24.0)
            .collect();
        let positions: Vec<DVec3> = angles
            .iter()
            .map(|a| (u * a.cos() + v * a.sin()) * 10.0 + DVec3::new(3.0, 4.0, 5.0))
            .collect();
        let velocities: Vec<DVec3> = angles.iter().map(|a| -u * a.sin() + v * a.cos()).collect();
        let mill = Frame::new(1.0, positions.clone(), velocities);
        let found = mill_axis(&mill).expect("a mill");
        assert!((found - axis).length() < 1e-12, "{found}");
        let (_, _, towards_viewer) = View::along(found).basis();
        assert!((towards_viewer - axis).length() < 1e-12);
        let parallel = Frame::new(1.0, positions, vec![DVec3::X; 24]);
        assert_eq!(mill_axis(&parallel), None);
    }
}
