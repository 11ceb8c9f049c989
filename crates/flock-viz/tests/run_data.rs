//! Reading a run directory back: `metrics.csv`, `trajectory.csv`, and the errors for bad files.

use std::fs;
use std::path::Path;

use flock_viz::{RunData, VizError, load_metrics, load_trajectory};
use glam::DVec3;

use crate::support::temp_dir;

const METRICS: &str = "\
t,connectivity,giant_component,cohesion_radius,deviation_energy,velocity_mismatch,min_distance,collisions,energy,obstacle_clearance,inside_obstacles
0,0.5,0.5,10,0.1,0.2,3,0,12.5,4,0
0.2,1,1,9.5,0.05,0.1,3.5,0,11,4.5,0
";

/// Two frames of three agents, rows of a frame not in id order.
const TRAJECTORY_2D: &str = "\
t,id,x,y,vx,vy
0,2,20,0,1,0
0,0,0,0,1,0
0,1,10,0,1,0
0.2,0,0.2,0,1,0
0.2,1,10.2,0,1,0
0.2,2,20.2,0,1,0
";

fn write_run(dir: &Path, metrics: &str, trajectory: &str) {
    fs::write(dir.join("metrics.csv"), metrics).unwrap();
    fs::write(dir.join("trajectory.csv"), trajectory).unwrap();
}

/// A run with faults reads back each frame's failed agents from the trajectory's last column.
#[test]
fn failed_agents_read_back_frame_by_frame() {
    // a directory of its own, created and removed by tempfile alone
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let trajectory = "\
t,id,x,y,vx,vy,failed
0,0,0,0,1,0,0
0,1,10,0,1,0,0
0.2,0,0.2,0,1,0,0
0.2,1,10,0,0,0,1
";
    write_run(dir, METRICS, trajectory);
    let run = RunData::load(dir).unwrap();
    assert_eq!(run.frames[0].failed, [false, false]);
    assert_eq!(run.frames[1].failed, [false, true]);
    assert!(run.frames[1].has_failed(1) && !run.frames[1].has_failed(0));
    assert_eq!(run.frames[1].failed_count(), 1);
    // without the column, no agent has failed
    write_run(dir, METRICS, TRAJECTORY_2D);
    let run = RunData::load(dir).unwrap();
    assert!(run.frames[1].failed.is_empty() && !run.frames[1].has_failed(2));
}

#[test]
fn a_2d_run_reads_back() {
    let dir_tmp = temp_dir("run-2d");
    let dir = dir_tmp.path();
    write_run(dir, METRICS, TRAJECTORY_2D);
    let run = RunData::load(dir).unwrap();
    assert_eq!(run.dim, 2);
    assert_eq!(run.metrics.len(), 2);
    assert_eq!(run.metrics.time(), &[0.0, 0.2]);
    assert_eq!(
        run.metrics.column("obstacle_clearance"),
        Some(&[4.0, 4.5][..])
    );
    assert_eq!(run.frames.len(), 2);
    assert_eq!(run.frames[0].t, 0.0);
    assert_eq!(
        run.frames[0].positions,
        [
            DVec3::ZERO,
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(20.0, 0.0, 0.0)
        ]
    );
    assert_eq!(run.frames[1].velocities[2], DVec3::X);
    let scene = run.scene(12.0);
    assert_eq!((scene.dim, scene.range, scene.frames.len()), (2, 12.0, 2));
    assert_eq!(scene.edges(0), [(0, 1), (1, 2)]);
}

#[test]
fn a_3d_trajectory_reads_back() {
    let dir_tmp = temp_dir("run-3d");
    let dir = dir_tmp.path();
    let path = dir.join("trajectory.csv");
    fs::write(
        &path,
        "t,id,x,y,z,vx,vy,vz\n0,0,1,2,3,4,5,6\n0,1,-1,-2,-3,0,0,0\n",
    )
    .unwrap();
    let (dim, frames) = load_trajectory(&path).unwrap();
    assert_eq!(dim, 3);
    assert_eq!(frames[0].positions[0], DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(frames[0].velocities[0], DVec3::new(4.0, 5.0, 6.0));
}

/// The message of the error of loading `trajectory` (with good metrics), with the directory
/// replaced by `DIR`.
fn trajectory_error(name: &str, trajectory: &str) -> String {
    let dir_tmp = temp_dir(name);
    let dir = dir_tmp.path();
    write_run(dir, METRICS, trajectory);
    let e = RunData::load(dir).unwrap_err();
    assert!(matches!(e, VizError::Parse { .. }), "{e:?}");
    e.to_string().replace(&dir.display().to_string(), "DIR")
}

#[test]
fn malformed_lines_are_named_by_file_and_line() {
    assert_eq!(
        trajectory_error("bad-number", "t,id,x,y,vx,vy\n0,0,0,0,1,0\n0,1,abc,0,1,0\n"),
        "DIR/trajectory.csv:3: field 3 (\"x\") is \"abc\", not a number"
    );
    assert_eq!(
        trajectory_error("short-line", "t,id,x,y,vx,vy\n0,0,0,0,1\n"),
        "DIR/trajectory.csv:2: expected 6 fields (as the header), found 5"
    );
    assert_eq!(
        trajectory_error("bad-header", "t,id,x,vx\n"),
        "DIR/trajectory.csv:1: expected the header \"t,id,x,y,vx,vy\" (2D) or \
         \"t,id,x,y,z,vx,vy,vz\" (3D), found \"t,id,x,vx\""
    );
    assert_eq!(
        trajectory_error("repeated-id", "t,id,x,y,vx,vy\n0,0,0,0,1,0\n0,0,1,0,1,0\n"),
        "DIR/trajectory.csv:3: id 0 appears twice at t = 0"
    );
    assert_eq!(
        trajectory_error("bad-id", "t,id,x,y,vx,vy\n0,0,0,0,1,0\n0,7,1,0,1,0\n"),
        "DIR/trajectory.csv:3: id 7 is not an agent index: the frame at t = 0 has 2 rows, ids 0 to 1"
    );
    assert_eq!(
        trajectory_error(
            "missing-agent",
            "t,id,x,y,vx,vy\n0,0,0,0,1,0\n0,1,1,0,1,0\n1,0,0,0,1,0\n"
        ),
        "DIR/trajectory.csv:4: the frame at t = 1 has 1 rows, the first frame has 2: every frame \
         lists every agent"
    );
    assert_eq!(
        trajectory_error(
            "time-backwards",
            "t,id,x,y,vx,vy\n1,0,0,0,1,0\n0,0,1,0,1,0\n"
        ),
        "DIR/trajectory.csv:3: t = 0 after t = 1: rows must be in time order"
    );
}

#[test]
fn malformed_metrics_are_named_by_file_and_line() {
    let dir_tmp = temp_dir("bad-metrics");
    let dir = dir_tmp.path();
    let path = dir.join("metrics.csv");
    fs::write(&path, "t,connectivity\n0,1\n0.2\n").unwrap();
    let message = load_metrics(&path).unwrap_err().to_string();
    assert_eq!(
        message,
        format!(
            "{}:3: expected 2 fields (as the header), found 1",
            path.display()
        )
    );
    fs::write(&path, "time,connectivity\n0,1\n").unwrap();
    let message = load_metrics(&path).unwrap_err().to_string();
    assert!(
        message.contains("metrics.csv:1: the header has no \"t\" column"),
        "{message}"
    );
}

#[test]
fn a_missing_file_is_named() {
    let dir_tmp = temp_dir("missing");
    let dir = dir_tmp.path();
    let e = RunData::load(dir).unwrap_err();
    assert!(matches!(e, VizError::Io { ref path, .. } if path.ends_with("metrics.csv")));
    assert!(e.to_string().contains("metrics.csv"));
}
