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
    let html = player_html(&lattice_scene(), &PlayerOptions::default()).unwrap();
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
    let html = player_html(&lattice_scene(), &PlayerOptions::default()).unwrap();
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
    let html = player_html(&lattice_scene(), &PlayerOptions::default()).unwrap();
    assert_eq!(data(&html).get("failed"), None);
    let mut scene = lattice_scene();
    let mut failed = vec![false; AGENTS];
    failed[5] = true;
    scene.frames[3] = scene.frames[3].clone().with_failed(failed);
    let html = player_html(&scene, &PlayerOptions::default()).unwrap();
    let data = data(&html);
    let lists = data.get("failed").expect("the failed agents").array();
    assert_eq!(lists.len(), FRAMES);
    assert!(lists[2].array().is_empty());
    assert_eq!(lists[3].array(), [Json::Number(5.0)]);
    assert!(data.get("colours").unwrap().get("failed").is_some());
}

#[test]
fn three_d_pages_offer_a_top_view() {
    let html = player_html(&cube_scene(), &PlayerOptions::default()).unwrap();
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
    let html = player_html(&scene, &PlayerOptions::default()).unwrap();
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
    let html = player_html(&lattice_scene(), &options).unwrap();
    assert_eq!(data(&html).get("t").unwrap().array().len(), 2);
    assert!(player_html(&Scene::new(2, 1.0), &options).is_err());
}
