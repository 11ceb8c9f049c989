//! The self-contained HTML player.

use flock_viz::{PlayerOptions, Scene, player_html};

use crate::support::{AGENTS, FRAMES, Json, cube_scene, lattice_scene};

/// The JSON data embedded in the page.
fn data(html: &str) -> Json {
    let start = html
        .find(r#"<script id="flock-data" type="application/json">"#)
        .expect("the data script");
    let rest = &html[start..];
    let json = &rest[rest.find('>').unwrap() + 1..rest.find("</script>").unwrap()];
    Json::parse(json).unwrap()
}

#[test]
fn the_page_has_its_controls_and_no_url() {
    let html = player_html(&lattice_scene(), None, &PlayerOptions::default()).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"));
    for id in ["play", "scrub", "speed", "edges", "zoom", "canvas", "time"] {
        assert!(html.contains(&format!("id=\"{id}\"")), "#{id}");
    }
    assert!(!html.contains("id=\"view\""), "2D runs have one view");
    assert!(!html.contains("http://") && !html.contains("https://"));
    assert!(!html.contains("http"));
    assert!(!html.contains("<script src") && !html.contains("<link"));
    assert!(html.contains(&format!("max=\"{}\"", FRAMES - 1)));
}

#[test]
fn the_embedded_data_describes_every_frame() {
    let html = player_html(&lattice_scene(), None, &PlayerOptions::default()).unwrap();
    let data = data(&html);
    assert_eq!(data.get("dim"), Some(&Json::Number(2.0)));
    assert_eq!(data.get("range"), Some(&Json::Number(8.4)));
    assert_eq!(data.get("t").unwrap().array().len(), FRAMES);
    let q = data.get("q").unwrap().array();
    assert_eq!(q.len(), FRAMES);
    assert!(q.iter().all(|f| f.array().len() == 2 * AGENTS));
    assert_eq!(
        q[1].array()[0],
        Json::Number(2.0),
        "agent 0 at x = 2 at t = 1"
    );
    assert_eq!(
        data.get("p").unwrap().array()[0].array()[0],
        Json::Number(2.0)
    );
    assert_eq!(data.get("g").unwrap().array().len(), FRAMES);
    let views = data.get("views").unwrap().array();
    assert_eq!(views.len(), 1);
    assert_eq!(views[0].get("obstacles").unwrap().array().len(), 1);
    assert_eq!(views[0].get("window").unwrap().array().len(), 4);
}

/// A run with faults lists each frame's failed agents for the script, which draws them as
/// crosses; a run without failures has no such list.
#[test]
fn the_data_lists_each_frames_failed_agents() {
    let html = player_html(&lattice_scene(), None, &PlayerOptions::default()).unwrap();
    assert_eq!(data(&html).get("failed"), None);
    let mut scene = lattice_scene();
    let mut failed = vec![false; AGENTS];
    failed[5] = true;
    scene.frames[3] = scene.frames[3].clone().with_failed(failed);
    let html = player_html(&scene, None, &PlayerOptions::default()).unwrap();
    let data = data(&html);
    let lists = data.get("failed").expect("the failed agents").array();
    assert_eq!(lists.len(), FRAMES);
    assert!(lists[2].array().is_empty());
    assert_eq!(lists[3].array(), [Json::Number(5.0)]);
    assert!(data.get("colours").unwrap().get("failed").is_some());
}

#[test]
fn three_d_pages_offer_a_top_view() {
    let html = player_html(&cube_scene(), None, &PlayerOptions::default()).unwrap();
    assert!(html.contains("id=\"view\""));
    let data = data(&html);
    assert_eq!(data.get("dim"), Some(&Json::Number(3.0)));
    let views = data.get("views").unwrap().array();
    assert_eq!(views.len(), 2);
    assert_eq!(views[1].get("name"), Some(&Json::String("top".into())));
    assert_eq!(data.get("q").unwrap().array()[0].array().len(), 3 * 27);
}

#[test]
fn titles_are_escaped_and_non_finite_numbers_are_null() {
    let mut scene = lattice_scene();
    scene.title = "</script><b>&\"".into();
    scene.frames[0].positions[3].x = f64::NAN;
    let html = player_html(&scene, None, &PlayerOptions::default()).unwrap();
    assert!(!html.contains("</script><b>"));
    let data = data(&html);
    assert_eq!(
        data.get("title"),
        Some(&Json::String("</script><b>&\"".into()))
    );
    assert_eq!(data.get("q").unwrap().array()[0].array()[6], Json::Null);
}

#[test]
fn long_runs_are_subsampled_and_empty_scenes_refused() {
    let options = PlayerOptions {
        max_frames: 2,
        ..PlayerOptions::default()
    };
    let html = player_html(&lattice_scene(), None, &options).unwrap();
    assert_eq!(data(&html).get("t").unwrap().array().len(), 2);
    assert!(player_html(&Scene::new(2, 1.0), None, &options).is_err());
}

/// The readout holds each metric column (but `t`) at the record nearest each frame shown, in the
/// readout's order, labelled, to 4 significant digits; a column it does not know by its name.
#[test]
fn the_readout_holds_each_measure_at_the_frames_record() {
    let times: Vec<f64> = (0..FRAMES).map(|k| k as f64).collect();
    let metrics = flock_viz::Metrics::from_columns(vec![
        ("t".into(), times.clone()),
        ("velocity_mismatch".into(), vec![1.234_567e-5; FRAMES]),
        (
            "my_measure".into(),
            times.iter().map(|t| 10.0 * t).collect(),
        ),
        (
            "connectivity".into(),
            times.iter().map(|t| t / 4.0).collect(),
        ),
    ])
    .unwrap();
    let options = PlayerOptions {
        max_frames: 3,
        ..PlayerOptions::default()
    };
    let html = player_html(&lattice_scene(), Some(&metrics), &options).unwrap();
    assert!(html.contains("id=\"readout\""));
    let page = data(&html);
    let measures = page.get("measures").unwrap().array();
    let labels: Vec<_> = measures.iter().map(|m| m.get("label").cloned()).collect();
    assert_eq!(
        labels,
        [
            Some(Json::String("connectivity C".into())),
            Some(Json::String("velocity mismatch K̃".into())),
            Some(Json::String("my measure".into())),
        ]
    );
    // frames 0, 2, 4 of 5 (t = 0, 2, 4)
    let values = |k: usize| measures[k].get("v").unwrap().array().to_vec();
    assert_eq!(values(0), [0.0, 0.5, 1.0].map(Json::Number));
    assert_eq!(values(1), [1.235e-5; 3].map(Json::Number));
    assert_eq!(values(2), [0.0, 20.0, 40.0].map(Json::Number));
    assert_eq!(measures[1].get("unit"), Some(&Json::String("m²/s²".into())));
    // without metrics, an empty readout (t only)
    let html = player_html(&lattice_scene(), None, &options).unwrap();
    assert_eq!(data(&html).get("measures").unwrap().array().len(), 0);
}

/// Agents closer than 10⁻³ d are one point: the page lists it with the first agent and the count,
/// at the frames where they are merged only.
#[test]
fn merged_agents_are_listed_with_their_count() {
    let mut scene = lattice_scene().with_desired_distance(7.0);
    let html = player_html(&scene, None, &PlayerOptions::default()).unwrap();
    assert_eq!(data(&html).get("merged"), None, "no agents merged");
    // at frame 2, agents 4 and 9 join agent 1 (within 10⁻³ · 7 m of it)
    let p1 = scene.frames[2].positions[1];
    scene.frames[2].positions[4] = p1 + glam::DVec3::new(0.005, 0.0, 0.0);
    scene.frames[2].positions[9] = p1 + glam::DVec3::new(0.0, 0.006, 0.0);
    let html = player_html(&scene, None, &PlayerOptions::default()).unwrap();
    let page = data(&html);
    let merged = page.get("merged").expect("merged points").array();
    assert_eq!(merged.len(), FRAMES);
    assert_eq!(merged[2].array(), [1.0, 3.0].map(Json::Number));
    assert!(merged[1].array().is_empty() && merged[3].array().is_empty());
    // 10⁻³ d is the bound: 0.008 m apart is not merged at d = 7 m
    scene.frames[2].positions[9] = p1 + glam::DVec3::new(0.0, 0.008, 0.0);
    let html = player_html(&scene, None, &PlayerOptions::default()).unwrap();
    let merged = data(&html).get("merged").unwrap().array().to_vec();
    assert_eq!(merged[2].array(), [1.0, 2.0].map(Json::Number));
}

/// A byte budget subsamples the frames evenly, first and last kept, until the page fits, and the
/// page says so; without a budget every frame is embedded and nothing is said.
#[test]
fn a_byte_budget_subsamples_the_frames_and_the_page_says_so() {
    let mut scene = Scene::new(2, 8.4).with_title("200 agents, 501 frames");
    for k in 0..501 {
        let t = 0.2 * k as f64;
        let q: Vec<glam::DVec2> = (0..200)
            .map(|i| {
                glam::DVec2::new(
                    300.0 * (i as f64 * 0.618).fract() + t,
                    300.0 * (i as f64 * 0.377).fract(),
                )
            })
            .collect();
        scene.frames.push(flock_viz::Frame::from_vectors(
            t,
            &q,
            &vec![glam::DVec2::X; 200],
        ));
    }
    let whole = player_html(&scene, None, &PlayerOptions::default()).unwrap();
    assert!(whole.len() > 1_500_000, "{} bytes", whole.len());
    assert!(!whole.contains("id=\"note\""));
    let options = PlayerOptions {
        max_bytes: Some(1_000_000),
        ..PlayerOptions::default()
    };
    let html = player_html(&scene, None, &options).unwrap();
    assert!(html.len() <= 1_000_000, "{} bytes", html.len());
    assert!(
        html.len() > 800_000,
        "uses the budget: {} bytes",
        html.len()
    );
    let t = data(&html).get("t").unwrap().array().to_vec();
    let shown = t.len();
    assert_eq!(t[0], Json::Number(0.0));
    assert_eq!(t[shown - 1], Json::Number(100.0), "the last frame is kept");
    // evenly: the gaps differ by at most one recorded frame (0.2 s)
    let gaps: Vec<f64> = t
        .windows(2)
        .map(|w| match (&w[0], &w[1]) {
            (Json::Number(a), Json::Number(b)) => b - a,
            _ => panic!("times are numbers"),
        })
        .collect();
    let (lo, hi) = gaps.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &g| {
        (lo.min(g), hi.max(g))
    });
    assert!(hi - lo <= 0.2 + 1e-9, "gaps from {lo} to {hi}");
    assert!(
        html.contains(&format!(
            "{shown} of 501 frames, evenly spaced, to fit 1 MB"
        )),
        "the note"
    );
    let tiny = PlayerOptions {
        max_bytes: Some(10_000),
        ..PlayerOptions::default()
    };
    let error = player_html(&scene, None, &tiny).unwrap_err().to_string();
    assert!(error.contains("raise max_bytes"), "{error}");
}
