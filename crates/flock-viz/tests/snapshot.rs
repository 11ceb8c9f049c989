//! Snapshots (TAC 2006 Figs. 10–13): markers, edges, obstacles, γ-agent, labels, PNG output.

use approx::assert_abs_diff_eq;
use flock_viz::snapshot::DEPTH_FADE;
use flock_viz::style::{BACKGROUND, EDGE, FAILED, GAMMA, NEAR_EDGE, OBSTACLE, TRAIL, blend};
use flock_viz::{Frame, Scene, SnapshotOptions, View, VizError, snapshot_png, snapshot_svg};
use glam::DVec2;

use crate::support::{
    AGENTS, EDGES, agent_fades, agent_markers, count_marks, cube_scene, decode_png, lattice_scene,
    styled,
};

#[test]
fn one_marker_per_agent_and_one_line_per_edge_in_each_panel() {
    let scene = lattice_scene();
    let svg = snapshot_svg(&scene, &[0, 4], &SnapshotOptions::default()).unwrap();
    assert!(svg.starts_with("<svg"));
    assert_eq!(agent_markers(&svg), 2 * AGENTS);
    assert_eq!(scene.edges(0).len(), EDGES);
    assert_eq!(count_marks(&svg, "polyline", "stroke", EDGE), 2 * EDGES);
    assert_eq!(count_marks(&svg, "polygon", "fill", GAMMA), 2);
    // The disc obstacle is within the window of the last frame only.
    assert_eq!(count_marks(&svg, "polygon", "fill", OBSTACLE), 1);
}

/// A run with faults: the failed agents of a frame are crosses (two strokes of [`FAILED`] each)
/// instead of triangles, and the panel's title counts them; a frame without failures is drawn as
/// before.
#[test]
fn failed_agents_are_crosses_and_the_title_counts_them() {
    let mut scene = lattice_scene();
    let mut failed = vec![false; AGENTS];
    failed[0] = true;
    failed[7] = true;
    scene.frames[2] = scene.frames[2].clone().with_failed(failed);
    let svg = snapshot_svg(&scene, &[2], &SnapshotOptions::default()).unwrap();
    assert_eq!(agent_markers(&svg), AGENTS - 2);
    assert_eq!(count_marks(&svg, "polyline", "stroke", FAILED), 4);
    assert!(
        svg.contains("t = 2 s, 2 failed (×)"),
        "the title counts them"
    );
    let svg = snapshot_svg(&scene, &[1], &SnapshotOptions::default()).unwrap();
    assert_eq!(agent_markers(&svg), AGENTS);
    assert_eq!(count_marks(&svg, "polyline", "stroke", FAILED), 0);
    assert!(svg.contains("t = 1 s") && !svg.contains("failed"));
}

#[test]
fn panels_have_titles_axis_labels_and_units() {
    let svg = snapshot_svg(&lattice_scene(), &[0, 2, 4], &SnapshotOptions::default()).unwrap();
    for text in [
        "synthetic lattice",
        "t = 0 s",
        "t = 2 s",
        "t = 4 s",
        "x (m)",
        "y (m)",
    ] {
        assert!(svg.contains(text), "{text} missing");
    }
    let svg = snapshot_svg(
        &lattice_scene(),
        &[0],
        &styled(|style| style.length_unit = "d".into()),
    )
    .unwrap();
    assert!(svg.contains("x (d)"));
}

#[test]
fn markers_point_along_the_velocity() {
    // One agent moving up: the triangle's tip (its highest point on the page) lies above the
    // others by 10 px (the marker length), as y grows upwards in data and downwards in pixels.
    let scene = Scene::new(2, 1.0).with_frame(Frame::from_vectors(
        0.0,
        &[DVec2::ZERO],
        &[DVec2::new(0.0, 3.0)],
    ));
    let svg = snapshot_svg(&scene, &[0], &SnapshotOptions::default()).unwrap();
    let points = first_triangle(&svg);
    assert_eq!(points.len(), 3);
    let (tip, base) = (points[0], [points[1], points[2]]);
    assert!(base.iter().all(|b| b.1 - tip.1 >= 9), "{points:?}");
    assert!((base[0].0 + base[1].0 - 2 * tip.0).abs() <= 1, "{points:?}");
}

#[test]
fn agents_at_rest_are_dots_and_trails_follow_the_agents() {
    let mut scene = lattice_scene();
    scene.frames[0].velocities.fill(glam::DVec3::ZERO);
    let svg = snapshot_svg(&scene, &[0], &SnapshotOptions::default()).unwrap();
    assert_eq!(
        count_marks(&svg, "circle", "fill", flock_viz::style::AGENT),
        AGENTS
    );
    let with_trails = styled(|style| style.trail = 2);
    let svg = snapshot_svg(&scene, &[4], &with_trails).unwrap();
    assert_eq!(count_marks(&svg, "polyline", "stroke", TRAIL), AGENTS);
    // The γ-agent's path is drawn in its colour.
    assert_eq!(count_marks(&svg, "polyline", "stroke", GAMMA), 1);
    // dotted (Tanner et al. 2003 Figs. 3–8): a dot at each recorded position, frames 2 to 4
    let dotted = styled(|style| {
        style.trail = 2;
        style.dotted_trails = true;
    });
    let svg = snapshot_svg(&scene, &[4], &dotted).unwrap();
    assert_eq!(count_marks(&svg, "polyline", "stroke", TRAIL), 0);
    assert_eq!(count_marks(&svg, "circle", "fill", TRAIL), 3 * AGENTS);
    assert_eq!(count_marks(&svg, "circle", "fill", GAMMA), 3);
}

#[test]
fn three_d_runs_are_projected_with_a_chosen_view_and_a_top_view() {
    let scene = cube_scene();
    let oblique = snapshot_svg(&scene, &[0, 2], &SnapshotOptions::default()).unwrap();
    assert_eq!(agent_markers(&oblique), 2 * 27);
    assert!(oblique.contains("u (m)") && oblique.contains("v (m)"));
    assert!(oblique.contains("view az -60°, el 30°"));
    let top = snapshot_svg(&scene, &[0], &styled(|style| style.view = View::TOP)).unwrap();
    assert!(top.contains("x (m)") && top.contains("top view"));
    assert_eq!(agent_markers(&top), 27);
    assert_ne!(oblique, top);
}

#[test]
fn the_png_has_the_requested_size_and_more_than_one_colour() {
    let options = SnapshotOptions {
        panel_size: (300, 240),
        ..SnapshotOptions::default()
    };
    let png = snapshot_png(&lattice_scene(), &[0, 2, 4], &options).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let image = decode_png(&png);
    // Three panels in a row, and the title band of 36 pixels.
    assert_eq!(image.size, (900, 276));
    let first = image.pixels[0];
    assert_eq!(first, [255, 255, 255], "white background");
    assert!(image.pixels.iter().any(|&p| p != first));
    let agent = flock_viz::style::AGENT;
    assert!(image.pixels.iter().filter(|&&p| p == agent).count() > 3 * AGENTS);
}

#[test]
fn bad_requests_are_refused() {
    let scene = lattice_scene();
    let options = SnapshotOptions::default();
    assert!(matches!(
        snapshot_svg(&scene, &[5], &options),
        Err(VizError::Invalid(m)) if m.contains("frame 5")
    ));
    assert!(snapshot_svg(&scene, &[], &options).is_err());
    assert!(snapshot_svg(&Scene::new(2, 1.0), &[0], &options).is_err());
    let tiny = SnapshotOptions {
        panel_size: (0, 10),
        ..SnapshotOptions::default()
    };
    assert!(snapshot_png(&scene, &[0], &tiny).is_err());
}

#[test]
fn walls_and_capsules_are_drawn_in_2d_and_3d() {
    use flock_viz::Drawable;
    use flock_viz::style::{OBSTACLE, WALL_PLANE};
    use glam::DVec3;

    // A 2D wall below the lattice fills the bottom of every panel; a capsule beside it.
    let scene = lattice_scene()
        .with_obstacle(Drawable::half_space(DVec2::new(0.0, -3.0), DVec2::Y))
        .with_obstacle(Drawable::capsule(
            DVec2::new(-2.5, 0.0),
            DVec2::new(-2.5, 14.0),
            1.0,
        ));
    let svg = snapshot_svg(&scene, &[0], &SnapshotOptions::default()).unwrap();
    assert_eq!(count_marks(&svg, "polygon", "fill", OBSTACLE), 2);

    // In 3D a floor is a light plane behind the flock (drawn first), a box stays solid.
    let cube =
        cube_scene().with_obstacle(Drawable::half_space(DVec3::new(0.0, 0.0, -5.0), DVec3::Z));
    let options = styled(|style| style.framing = flock_viz::Framing::Run);
    for view in [View::default(), View::TOP] {
        let mut seen = options.clone();
        seen.style.view = view;
        let svg = snapshot_svg(&cube, &[0], &seen).unwrap();
        assert_eq!(count_marks(&svg, "polygon", "fill", WALL_PLANE), 1);
        assert_eq!(
            count_marks(&svg, "polygon", "fill", OBSTACLE),
            2,
            "ball and box"
        );
        let plane = svg.find(&flock_viz::style::hex(WALL_PLANE)).unwrap();
        let solid = svg
            .find(&format!("fill=\"{}\"", flock_viz::style::hex(OBSTACLE)))
            .unwrap();
        assert!(plane < solid, "the plane is drawn first");
    }
    // Seen from the side, the floor is edge-on: a solid region.
    let mut side = options;
    side.style.view = View::new(-90.0, 0.0);
    let svg = snapshot_svg(&cube, &[0], &side).unwrap();
    assert_eq!(count_marks(&svg, "polygon", "fill", WALL_PLANE), 0);
    assert_eq!(count_marks(&svg, "polygon", "fill", OBSTACLE), 3);
}

/// Reynolds' rules made visible (ACC 2004 eq. 26–31): with `stress_edges`, an edge longer than d
/// (s_ij > 0, F⁺) is drawn in the attraction colour, a shorter one (F⁻) in the repulsion colour,
/// one within 1 % of d (F⁰) grey; without the option, or without d, every edge is grey.
#[test]
fn edges_are_coloured_by_the_sign_of_their_stress_weight() {
    use flock_viz::style::{ATTRACTION, REPULSION};
    // d = 7: a pair at 8 (attraction), one at 6 (repulsion), one at 7.01 (neutral)
    let q = [
        DVec2::new(0.0, 0.0),
        DVec2::new(8.0, 0.0),
        DVec2::new(0.0, 50.0),
        DVec2::new(6.0, 50.0),
        DVec2::new(50.0, 0.0),
        DVec2::new(57.01, 0.0),
    ];
    let scene = Scene::new(2, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec2::X; 6]));
    let stress = styled(|style| style.stress_edges = true);
    let count = |scene: &Scene, options: &SnapshotOptions, colour| {
        let svg = snapshot_svg(scene, &[0], options).unwrap();
        count_marks(&svg, "polyline", "stroke", colour)
    };
    let with_d = scene.clone().with_desired_distance(7.0);
    assert_eq!(count(&with_d, &stress, ATTRACTION), 1);
    assert_eq!(count(&with_d, &stress, REPULSION), 1);
    assert_eq!(count(&with_d, &stress, EDGE), 1);
    assert_eq!(count(&with_d, &SnapshotOptions::default(), EDGE), 3);
    assert_eq!(count(&scene, &stress, EDGE), 3, "no d: no stress colours");
}

/// Tanner et al. Figs. 3–8: a scene with a fixed interaction graph draws that graph, whatever the
/// distances, and velocity arrows when asked (one shaft and one head per moving agent).
#[test]
fn a_fixed_graph_is_drawn_instead_of_the_net_with_velocity_arrows() {
    use flock_viz::style::VELOCITY;
    let q = [
        DVec2::new(0.0, 0.0),
        DVec2::new(3.0, 0.0),
        DVec2::new(30.0, 0.0),
    ];
    let p = [DVec2::X, DVec2::Y, DVec2::ZERO];
    let scene = Scene::new(2, 8.4)
        .with_frame(Frame::from_vectors(0.0, &q, &p))
        .with_interaction_graph([(2, 0)]);
    assert_eq!(
        scene.edges(0),
        vec![(0, 2)],
        "the graph, not the net's (0, 1)"
    );
    let svg = snapshot_svg(&scene, &[0], &SnapshotOptions::default()).unwrap();
    assert_eq!(count_marks(&svg, "polyline", "stroke", EDGE), 1);
    assert_eq!(count_marks(&svg, "polyline", "stroke", VELOCITY), 0);
    let arrows = styled(|style| style.velocity_arrows = true);
    let svg = snapshot_svg(&scene, &[0], &arrows).unwrap();
    assert_eq!(count_marks(&svg, "polyline", "stroke", VELOCITY), 2 * 2);
    let bad = Scene::new(2, 8.4)
        .with_frame(Frame::from_vectors(0.0, &q, &p))
        .with_interaction_graph([(0, 3)]);
    assert!(matches!(
        snapshot_svg(&bad, &[0], &SnapshotOptions::default()),
        Err(VizError::Invalid(_))
    ));
}

#[test]
fn three_d_panels_are_depth_cued_far_agents_first_and_faded() {
    let scene = cube_scene();
    let view = View::default();
    let svg = snapshot_svg(&scene, &[0], &styled(|style| style.view = view)).unwrap();
    let fades = agent_fades(&svg);
    assert_eq!(fades.len(), 27);
    // drawn far to near: the fade falls from DEPTH_FADE at the farthest agent to 0 at the nearest
    assert!(fades.windows(2).all(|w| w[0] >= w[1]), "{fades:?}");
    assert_abs_diff_eq!(fades[0], DEPTH_FADE, epsilon = 0.01);
    assert_eq!(fades[26], 0.0);
    // and each agent faded by its depth: the cube's middle layer in depth half way
    let depths: Vec<f64> = scene.frames[0]
        .positions
        .iter()
        .map(|&q| view.depth(q))
        .collect();
    let (far, near) = depths
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &z| {
            (lo.min(z), hi.max(z))
        });
    let mut expected: Vec<f64> = depths
        .iter()
        .map(|z| DEPTH_FADE * (near - z) / (near - far))
        .collect();
    expected.sort_by(|a, b| b.total_cmp(a));
    for (fade, expected) in fades.iter().zip(&expected) {
        assert_abs_diff_eq!(fade, expected, epsilon = 0.01);
    }
    // the edges drawn far to near, light to dark: shades of NEAR_EDGE at their middles' depths
    let mut bare = scene.clone();
    bare.obstacles.clear();
    let svg = snapshot_svg(&bare, &[0], &styled(|style| style.view = view)).unwrap();
    let greys: Vec<u8> = svg
        .split("<polyline")
        .skip(1)
        .filter_map(|e| e.split("stroke=\"#").nth(1)?.get(..2))
        .map(|g| u8::from_str_radix(g, 16).unwrap())
        .filter(|&g| g != 0) // the axes and the frame, in ink
        .collect();
    assert_eq!(greys.len(), 54); // the cube's 3 · 9 · 2 edges
    assert!(greys.windows(2).all(|w| w[0] >= w[1]), "{greys:?}");
    let shade = |fade: f64| blend(NEAR_EDGE, BACKGROUND, fade)[0];
    // the nearest edge: its middle half an edge behind the nearest corner, of the depth range
    // 3 · 7 · (|w_x| + |w_y| + |w_z|) in this view
    let w = view.basis().2;
    let range = 14.0 * (w.x.abs() + w.y.abs() + w.z.abs());
    let nearest_edge = DEPTH_FADE * 3.5 * w.x.abs().min(w.y.abs()).min(w.z.abs()) / range;
    assert_eq!(greys[53], shade(nearest_edge));
    assert!(greys[0] > shade(0.6) && greys[53] < shade(0.1), "{greys:?}");
    // 2D panels are not cued
    let flat = snapshot_svg(&lattice_scene(), &[0], &SnapshotOptions::default()).unwrap();
    assert!(agent_fades(&flat).iter().all(|&f| f == 0.0));
}

/// The pixel corners of the first agent's triangle in an SVG.
fn first_triangle(svg: &str) -> Vec<(i32, i32)> {
    let polygon = svg
        .split('<')
        .find(|e| e.starts_with("polygon ") && e.contains("#1F4E9C"))
        .unwrap();
    polygon
        .split("points=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap()
        .split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// The length in pixels, along its velocity (+x), of the first agent's triangle.
fn first_marker_length(svg: &str) -> i32 {
    let xs: Vec<i32> = first_triangle(svg).iter().map(|p| p.0).collect();
    xs.iter().max().unwrap() - xs.iter().min().unwrap()
}

#[test]
fn markers_shrink_in_wide_panels_so_that_edges_show_between_them() {
    // Two neighbours d = 7 apart and a third agent `far` away along x: the panel spans ≈ far
    // metres over its 394 pixels.
    let scene = |far: f64| {
        let q = [DVec2::ZERO, DVec2::new(7.0, 0.0), DVec2::new(far, 0.0)];
        Scene::new(2, 8.4)
            .with_desired_distance(7.0)
            .with_frame(Frame::from_vectors(0.0, &q, &[DVec2::X; 3]))
    };
    let options = SnapshotOptions::default(); // markers of 10 px
    // narrow: d spans ≈ 39 px, the marker keeps its 10 px
    let narrow = snapshot_svg(&scene(70.0), &[0], &options).unwrap();
    assert!((9..=10).contains(&first_marker_length(&narrow)));
    // wide: d spans ≈ 7.9 px, the marker 0.4 d ≈ 3.2 px, leaving ≈ 4.7 px of the edge bare
    let wide = snapshot_svg(&scene(350.0), &[0], &options).unwrap();
    let length = first_marker_length(&wide);
    assert!((2..=4).contains(&length), "{length} px");
    // without a desired distance nothing says how far apart neighbours are: 10 px
    let mut unknown = scene(350.0);
    unknown.desired_distance = None;
    let unknown = snapshot_svg(&unknown, &[0], &options).unwrap();
    assert!((9..=10).contains(&first_marker_length(&unknown)));
}

#[test]
fn in_3d_an_obstacle_behind_the_flock_is_faded_and_one_before_it_is_not() {
    use flock_viz::Drawable;
    use glam::DVec3;

    // Seen from above: two agents at z = 0 and 7, a ball above them (nearer the viewer) and one
    // below (behind them), both projected between the agents.
    let q = [DVec3::ZERO, DVec3::new(7.0, 0.0, 7.0)];
    let scene = Scene::new(3, 8.4)
        .with_frame(Frame::from_vectors(0.0, &q, &[DVec3::X; 2]))
        .with_obstacle(Drawable::ball(DVec3::new(3.5, 0.0, 50.0), 2.0))
        .with_obstacle(Drawable::ball(DVec3::new(3.5, 0.0, -50.0), 2.0));
    let svg = snapshot_svg(&scene, &[0], &styled(|style| style.view = View::TOP)).unwrap();
    assert_eq!(count_marks(&svg, "polygon", "fill", OBSTACLE), 1);
    let behind = blend(OBSTACLE, BACKGROUND, DEPTH_FADE);
    assert_eq!(count_marks(&svg, "polygon", "fill", behind), 1);
}

/// Two agents moving along x across the wrap of a periodic box, and a third resting by the first
/// across the wrap, over ten frames.
fn wrapping_scene(periodic: bool) -> Scene {
    let size = 20.0;
    let mut scene = Scene::new(2, 3.0);
    for k in 0..10 {
        let x = (15.0 + 1.2 * f64::from(k)) % size;
        let q = [
            DVec2::new(x, 5.0),
            DVec2::new((x + 2.0) % size, 12.0),
            DVec2::new(0.5, 16.0),
            DVec2::new(19.0, 16.0),
        ];
        let p = [DVec2::X, DVec2::X, DVec2::ZERO, DVec2::ZERO];
        scene = scene.with_frame(Frame::from_vectors(f64::from(k), &q, &p));
    }
    if periodic {
        scene = scene.with_periodic_box(glam::DVec3::new(size, size, 0.0));
    }
    scene
}

/// A periodic scene draws its box and cuts the trails at the wrap: no segment spans the box.
#[test]
fn periodic_runs_draw_the_box_and_no_segment_across_the_wrap() {
    use flock_viz::style::PERIODIC_BOX;
    let options = styled(|style| {
        style.trail = 9;
        style.framing = flock_viz::Framing::Fixed {
            min: DVec2::new(-1.0, -1.0),
            max: DVec2::new(21.0, 21.0),
        };
    });
    let open = snapshot_svg(&wrapping_scene(false), &[9], &options).unwrap();
    let torus = snapshot_svg(&wrapping_scene(true), &[9], &options).unwrap();
    // open space: one trail per agent (those at rest too), the moving ones jumping back across
    // the box; no box
    assert_eq!(count_marks(&open, "polyline", "stroke", TRAIL), 4);
    assert_eq!(count_marks(&open, "polyline", "stroke", PERIODIC_BOX), 0);
    // the torus: each moving agent's trail in two runs, the box's four sides
    assert_eq!(count_marks(&torus, "polyline", "stroke", TRAIL), 6);
    assert_eq!(count_marks(&torus, "polyline", "stroke", PERIODIC_BOX), 4);
    // agents 2 and 3 are neighbours across the wrap (distance 1.5): an edge of the net, not drawn
    let scene = wrapping_scene(true);
    assert!(scene.edges(9).contains(&(2, 3)));
    assert!(!wrapping_scene(false).edges(9).contains(&(2, 3)));
    assert_eq!(
        count_marks(&torus, "polyline", "stroke", EDGE),
        scene.edges(9).len() - 1
    );
    let runs = scene.trail_runs(0, 0..10);
    assert_eq!(runs.iter().map(Vec::len).collect::<Vec<_>>(), [5, 5]);
    assert_eq!(wrapping_scene(false).trail_runs(0, 0..10).len(), 1);
}

/// In 3D the box is the twelve projected edges of the cuboid.
#[test]
fn periodic_box_in_3d_has_twelve_edges() {
    use flock_viz::style::PERIODIC_BOX;
    let q = [
        glam::DVec3::new(1.0, 2.0, 3.0),
        glam::DVec3::new(9.0, 8.0, 7.0),
    ];
    let scene = Scene::new(3, 2.0)
        .with_frame(Frame::from_vectors(0.0, &q, &[glam::DVec3::X; 2]))
        .with_periodic_box(glam::DVec3::new(10.0, 10.0, 10.0));
    let options = styled(|style| {
        style.view = View::new(30.0, 20.0);
        style.framing = flock_viz::Framing::Fixed {
            min: DVec2::new(-30.0, -30.0),
            max: DVec2::new(30.0, 30.0),
        };
    });
    let svg = snapshot_svg(&scene, &[0], &options).unwrap();
    assert_eq!(count_marks(&svg, "polyline", "stroke", PERIODIC_BOX), 12);
}
