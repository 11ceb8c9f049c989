//! Snapshots of a run as TAC 2006 Figs. 10–13 draw them: at chosen times, the α-agents as small
//! triangles pointing along their velocity, the edges of the proximity net between neighbours
//! (‖q_j − q_i‖ < r), obstacles filled grey, the γ-agent as a red diamond, optional trails; one
//! panel per time, each with equal axis scales and labelled axes. 3D runs are drawn as an
//! orthographic projection ([`View`]); [`View::TOP`] gives the top view.
//!
//! - [`snapshot_svg`], [`snapshot_png`]: a figure of one panel per chosen frame;
//!   [`snapshot_rgb`](crate::snapshot_rgb) one frame as pixels in memory.
//! - [`SnapshotOptions`]: panel size, view, framing, trails, edges, marker size, length unit.

use glam::{DVec2, DVec3};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::{
    Cartesian2d, ChartBuilder, ChartContext, Circle, DrawingArea, DrawingBackend, PathElement,
    Polygon,
};
use plotters::style::{Color, IntoFont, ShapeStyle, TextStyle};

use crate::draw::font::FONT_FAMILY;
use crate::draw::format;
use crate::draw::geometry::{Rect, circle_polygon, clip_polygon, clip_polyline, clip_segment};
use crate::draw::render::{self, Figure};
use crate::draw::style::{
    self, AGENT, ATTRACTION, BACKGROUND, EDGE, FAILED, GAMMA, INK, NEAR_EDGE, OBSTACLE,
    OBSTACLE_OUTLINE, PERIODIC_BOX, REPULSION, TRAIL, VELOCITY, WALL_PLANE,
};
use crate::error::VizError;
use crate::scene::drawable::{CIRCLE_SIDES, Drawable, Shape};
use crate::scene::frames::Scene;
use crate::scene::framing::{Framer, Framing};
use crate::scene::projection::View;

/// Edges within this fraction of d from d are drawn neutral (F⁰) when coloured by stress: s_ij = 0
/// holds only at exactly d, which round-off never gives.
pub const NEUTRAL_BAND: f64 = 0.01;

/// Height in pixels of the band that holds a figure's title.
const TITLE_BAND: u32 = 36;
/// Margins of a panel's plotting area (top, bottom, left, right), in pixels.
const MARGIN: (u32, u32, u32, u32) = (4, 6, 6, 18);
/// Height of the x-axis label area, in pixels.
const X_LABEL_AREA: u32 = 44;
/// Width of the y-axis label area, in pixels.
const Y_LABEL_AREA: u32 = 62;

/// How snapshots are drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct SnapshotOptions {
    /// The size of one panel in pixels (width, height).
    pub panel_size: (u32, u32),
    /// Panels per row of the figure.
    pub columns: usize,
    /// What each panel draws and how.
    pub style: PanelStyle,
}

impl Default for SnapshotOptions {
    fn default() -> Self {
        Self {
            panel_size: (480, 480),
            columns: 3,
            style: PanelStyle {
                framing: Framing::Flock,
                marker_size: 10.0,
                ..PanelStyle::default()
            },
        }
    }
}

/// What a panel draws and how, shared by snapshots and animations.
#[derive(Clone, Debug, PartialEq)]
pub struct PanelStyle {
    /// The projection of 3D runs (2D runs are drawn in their plane).
    pub view: View,
    /// Which part of the plane a panel shows.
    pub framing: Framing,
    /// How many earlier recorded frames each agent's trail goes back (0: no trails).
    pub trail: usize,
    /// Whether trails are dotted, a dot at every recorded position (at most
    /// [`MAX_TRAIL_DOTS`] per agent, evenly thinned), as Tanner et al. 2003 draw trajectories
    /// (Figs. 3–8); otherwise a line.
    pub dotted_trails: bool,
    /// Whether to draw the edges of the proximity net (of the scene's interaction graph, if any).
    pub edges: bool,
    /// Whether to colour each edge by the sign of its stress weight s_ij (ACC 2004 eq. 26–31,
    /// Reynolds' rules made visible): [`ATTRACTION`] for ‖q_j − q_i‖ > d (j ∈ F_i⁺, cohesion),
    /// [`REPULSION`] for ‖q_j − q_i‖ < d (j ∈ F_i⁻, separation), grey for the neutral friends F_i⁰,
    /// within [`NEUTRAL_BAND`] · d of d. Needs the scene's desired distance; grey edges without.
    pub stress_edges: bool,
    /// Whether to draw each agent's velocity as an arrow (Tanner et al. 2003, Figs. 3–8), the
    /// fastest of the frame three markers long.
    pub velocity_arrows: bool,
    /// The length of an agent's triangle, in pixels.
    pub marker_size: f64,
    /// The scenario's unit of length, for the axis labels.
    pub length_unit: String,
}

impl Default for PanelStyle {
    fn default() -> Self {
        Self {
            view: View::default(),
            framing: Framing::Run,
            trail: 0,
            dotted_trails: false,
            edges: true,
            stress_edges: false,
            velocity_arrows: false,
            marker_size: 9.0,
            length_unit: "m".to_owned(),
        }
    }
}

/// An SVG figure of `frames` (indices into `scene.frames`), one panel per frame, titled
/// `t = … s`, in rows of `options.columns`: the snapshots of TAC 2006 Figs. 10–13.
///
/// # Errors
/// [`VizError::Invalid`] when the scene cannot be drawn (no frames, a dimension other than 2 or
/// 3), `frames` is empty or holds an index out of range, or the panel size is out of bounds.
///
/// # Example
/// ```
/// use flock_viz::{Frame, Scene, SnapshotOptions, snapshot_svg};
/// use glam::DVec2;
///
/// let q = [DVec2::new(0.0, 0.0), DVec2::new(7.0, 0.0)];
/// let scene = Scene::new(2, 8.4).with_frame(Frame::from_vectors(0.0, &q, &[DVec2::X; 2]));
/// let svg = snapshot_svg(&scene, &[0], &SnapshotOptions::default()).unwrap();
/// assert!(svg.contains("t = 0 s"));
/// assert_eq!(svg.matches(r##"fill="#1F4E9C""##).count(), 2); // two agents
/// ```
pub fn snapshot_svg(
    scene: &Scene,
    frames: &[usize],
    options: &SnapshotOptions,
) -> Result<String, VizError> {
    render::svg(&Snapshot::new(scene, frames, options)?)
}

/// The figure of [`snapshot_svg`] as a PNG image (text rendered with the embedded font).
///
/// # Errors
/// As [`snapshot_svg`]; [`VizError::Encode`] if PNG encoding fails.
pub fn snapshot_png(
    scene: &Scene,
    frames: &[usize],
    options: &SnapshotOptions,
) -> Result<Vec<u8>, VizError> {
    render::png(&Snapshot::new(scene, frames, options)?)
}

/// A snapshot figure, checked and ready to draw.
struct Snapshot<'a> {
    scene: &'a Scene,
    frames: &'a [usize],
    options: &'a SnapshotOptions,
    columns: usize,
    rows: usize,
}

impl<'a> Snapshot<'a> {
    fn new(
        scene: &'a Scene,
        frames: &'a [usize],
        options: &'a SnapshotOptions,
    ) -> Result<Self, VizError> {
        check_frames(scene, frames)?;
        let columns = options.columns.clamp(1, frames.len());
        let rows = frames.len().div_ceil(columns);
        Ok(Self {
            scene,
            frames,
            options,
            columns,
            rows,
        })
    }

    fn title(&self) -> String {
        figure_title(self.scene, self.options.style.view)
    }
}

/// Checks that `scene` can be drawn and that `frames` chosen of it are some and all in range.
pub(crate) fn check_frames(scene: &Scene, frames: &[usize]) -> Result<(), VizError> {
    scene.validate()?;
    if frames.is_empty() {
        return Err(VizError::invalid("no frames chosen for the snapshot"));
    }
    if let Some(&k) = frames.iter().find(|&&k| k >= scene.frames.len()) {
        return Err(VizError::invalid(format!(
            "frame {k} chosen, but the scene has {} frames",
            scene.frames.len()
        )));
    }
    Ok(())
}

/// A figure's title: the scene's title, and for 3D runs the view.
pub(crate) fn figure_title(scene: &Scene, view: View) -> String {
    match (scene.title.is_empty(), scene.dim == 3) {
        (true, false) => String::new(),
        (true, true) => view.describe(),
        (false, false) => scene.title.clone(),
        (false, true) => format!("{} ({})", scene.title, view.describe()),
    }
}

impl Figure for Snapshot<'_> {
    fn size(&self) -> (u32, u32) {
        grid_size(
            self.options.panel_size,
            self.columns,
            self.rows,
            &self.title(),
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), VizError> {
        let body = below_title(root, &self.title())?;
        let panels = body.split_evenly((self.rows, self.columns));
        let style = &self.options.style;
        let framer = Framer::new(self.scene, style.view, style.trail);
        for (panel, &frame) in panels.iter().zip(self.frames) {
            draw_panel(panel, &framer, frame, style, &time_title(self.scene, frame))?;
        }
        Ok(())
    }
}

/// The size of `rows × columns` panels of `panel` pixels, under a title band unless `title` is empty.
pub(crate) fn grid_size(panel: (u32, u32), columns: usize, rows: usize, title: &str) -> (u32, u32) {
    let band = if title.is_empty() { 0 } else { TITLE_BAND };
    (
        panel.0.saturating_mul(columns as u32),
        panel.1.saturating_mul(rows as u32).saturating_add(band),
    )
}

/// Draws `title` centred in a band at the top of `root` (nothing when it is empty) and returns the
/// area below it.
pub(crate) fn below_title<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
) -> Result<DrawingArea<DB, Shift>, VizError> {
    if title.is_empty() {
        return Ok(root.clone());
    }
    let (top, body) = root.split_vertically(TITLE_BAND);
    top.titled(title, (FONT_FAMILY, 20).into_font().color(&style::rgb(INK)))
        .map_err(VizError::draw)?;
    Ok(body)
}

/// Text of the given size in the figures' font and ink.
pub(crate) fn text_style(size: u32) -> TextStyle<'static> {
    (FONT_FAMILY, size).into_font().color(&style::rgb(INK))
}

/// The chart of a snapshot panel: page coordinates in data units on both axes.
pub(crate) type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A page point as plotters takes it.
pub(crate) fn tuple(p: DVec2) -> (f64, f64) {
    (p.x, p.y)
}

/// A panel's title: the time of its frame, `t = … s`.
pub(crate) fn time_title(scene: &Scene, frame: usize) -> String {
    let frame = &scene.frames[frame];
    let t = format::number(frame.t, 2);
    match frame.failed_count() {
        0 => format!("t = {t} s"),
        failed => format!("t = {t} s, {failed} failed (×)"),
    }
}

/// Draws frame `frame` of the framer's scene in `area`: `title`, axes, obstacles, edges, trails,
/// agents and the γ-agent (3D scenes depth-cued: see [`DepthCue`]).
pub(crate) fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    framer: &Framer<'_>,
    frame: usize,
    panel: &PanelStyle,
    title: &str,
) -> Result<(), VizError> {
    let scene = framer.scene();
    panel_chart(
        area,
        framer,
        frame,
        (panel.framing, &panel.length_unit),
        title,
        |chart, window, per_pixel| {
            let marker = panel.marker_size * per_pixel;
            let cue = DepthCue::of(framer, frame);
            draw_periodic_box(chart, framer, window)?;
            draw_obstacles(chart, framer, window, &cue)?;
            if panel.edges {
                let stress = panel
                    .stress_edges
                    .then_some(framer.scene().desired_distance)
                    .flatten();
                draw_edges(chart, framer, frame, window, stress, &cue)?;
            }
            if panel.trail > 0 {
                draw_trails(chart, framer, frame, panel, window)?;
            }
            if panel.velocity_arrows {
                draw_velocities(chart, framer, frame, window, marker)?;
            }
            let agent_px = agent_marker_px(panel.marker_size, scene.desired_distance, per_pixel);
            draw_agents(
                chart,
                framer,
                frame,
                window,
                agent_px * per_pixel,
                agent_px,
                &cue,
            )?;
            draw_gamma(chart, framer, frame, window, marker)
        },
    )
}

/// A panel of frame `frame` in `area`: `title`, then labelled axes of equal scales around the
/// window that `framing` gives (lengths in `unit`), `draw`'s marks — called with the chart, the
/// window and the data units per pixel — and a frame around the plotting area.
pub(crate) fn panel_chart<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    framer: &Framer<'_>,
    frame: usize,
    (framing, unit): (Framing, &str),
    title: &str,
    draw: impl FnOnce(&mut Chart<'_, DB>, Rect, f64) -> Result<(), VizError>,
) -> Result<(), VizError> {
    let scene = framer.scene();
    let area = area.titled(title, text_style(17)).map_err(VizError::draw)?;

    // The plotting area in pixels, to give both axes the same scale.
    let (w, h) = area.dim_in_pixel();
    let plot_w = w.saturating_sub(MARGIN.2 + MARGIN.3 + Y_LABEL_AREA).max(1);
    let plot_h = h.saturating_sub(MARGIN.0 + MARGIN.1 + X_LABEL_AREA).max(1);
    let window = framer
        .window(framing, frame)
        .with_aspect(f64::from(plot_w) / f64::from(plot_h));
    let per_pixel = window.size().x / f64::from(plot_w);

    let mut chart = ChartBuilder::on(&area)
        .margin_top(MARGIN.0)
        .margin_bottom(MARGIN.1)
        .margin_left(MARGIN.2)
        .margin_right(MARGIN.3)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(window.min.x..window.max.x, window.min.y..window.max.y)
        .map_err(VizError::draw)?;
    debug_assert_eq!(chart.plotting_area().dim_in_pixel(), (plot_w, plot_h));
    let (x_name, y_name) = if scene.dim == 2 {
        ("x", "y")
    } else {
        framer.view().axis_names()
    };
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("{x_name} ({unit})"))
        .y_desc(format!("{y_name} ({unit})"))
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&|v| format::tick(*v))
        .y_label_formatter(&|v| format::tick(*v))
        .label_style(text_style(13))
        .axis_desc_style(text_style(14))
        .axis_style(style::rgb(INK))
        .draw()
        .map_err(VizError::draw)?;

    draw(&mut chart, window, per_pixel)?;

    // A frame around the plotting area, as the papers' figures have.
    let (lo, hi) = (window.min, window.max);
    chart
        .draw_series([PathElement::new(
            vec![
                (lo.x, lo.y),
                (hi.x, lo.y),
                (hi.x, hi.y),
                (lo.x, hi.y),
                (lo.x, lo.y),
            ],
            style::rgb(INK).stroke_width(1),
        )])
        .map_err(VizError::draw)?;
    Ok(())
}

/// Obstacles, filled grey and outlined, cut to the window; light wall planes first; in 3D an
/// obstacle wholly behind the flock's farthest agent faded by `cue` (one the flock is level with
/// or behind is full grey).
fn draw_obstacles<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    framer: &Framer<'_>,
    window: Rect,
    cue: &DepthCue,
) -> Result<(), VizError> {
    let scene = framer.scene();
    let world = framer.world_for(window);
    for (shape, front) in Drawable::project_all(&scene.obstacles, framer.view(), scene.dim, world) {
        let fade = |colour| front.map_or(colour, |depth| cue.fade_behind(colour, depth));
        let (polygon, fill) = match shape {
            Shape::Circle { centre, radius } => {
                (circle_polygon(centre, radius, CIRCLE_SIDES), OBSTACLE)
            }
            Shape::Polygon(points) => (points, OBSTACLE),
            Shape::Plane(points) => (points, WALL_PLANE),
        };
        let clipped = clip_polygon(&polygon, window);
        if clipped.len() < 3 {
            continue;
        }
        let points: Vec<(f64, f64)> = clipped.iter().map(|&p| tuple(p)).collect();
        let mut outline = points.clone();
        outline.push(points[0]);
        chart
            .draw_series([Polygon::new(points, style::rgb(fade(fill)).filled())])
            .map_err(VizError::draw)?;
        chart
            .draw_series([PathElement::new(
                outline,
                style::rgb(fade(OBSTACLE_OUTLINE)).stroke_width(1),
            )])
            .map_err(VizError::draw)?;
    }
    Ok(())
}

/// The net: a thin line per edge (grey, or coloured by the sign of its stress weight when `stress`
/// holds the desired distance d), far edges first and faded by `cue`.
pub(crate) fn draw_edges<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    framer: &Framer<'_>,
    frame: usize,
    window: Rect,
    stress: Option<f64>,
    cue: &DepthCue,
) -> Result<(), VizError> {
    let positions = &framer.scene().frames[frame].positions;
    let project = |i: u32| framer.project(positions[i as usize]);
    let colour = |i: u32, j: u32| match stress {
        Some(d) => {
            let stretch = (positions[j as usize] - positions[i as usize]).length() - d;
            if stretch > NEUTRAL_BAND * d {
                ATTRACTION
            } else if stretch < -NEUTRAL_BAND * d {
                REPULSION
            } else {
                EDGE
            }
        }
        None if cue.is_some() => NEAR_EDGE,
        None => EDGE,
    };
    // an edge across the wrap of a periodic box would span the box: it is not drawn
    let scene = framer.scene();
    let mut edges = scene.edges(frame);
    edges.retain(|&(i, j)| !scene.crosses_wrap(positions[i as usize], positions[j as usize]));
    if cue.is_some() {
        edges.sort_by(|&a, &b| {
            cue.edge_depth(a)
                .total_cmp(&cue.edge_depth(b))
                .then(a.cmp(&b))
        });
    }
    let lines: Vec<PathElement<(f64, f64)>> = edges
        .into_iter()
        .filter_map(|(i, j)| {
            clip_segment(project(i), project(j), window).map(|(a, b)| {
                let faded = cue.fade(colour(i, j), cue.edge_depth((i, j)));
                PathElement::new(vec![tuple(a), tuple(b)], style::rgb(faded).stroke_width(1))
            })
        })
        .collect();
    chart.draw_series(lines).map_err(VizError::draw)?;
    Ok(())
}

/// How far the farthest mark of a 3D panel is faded towards the background: depth cueing, the
/// near side of the net drawn dark and the far side light, so that a projected 3D lattice reads
/// front from back.
pub const DEPTH_FADE: f64 = 0.8;

/// The depth cueing of one 3D frame: its agents' depths in the view and their range (none in
/// 2D).
#[derive(Clone, Debug)]
pub(crate) struct DepthCue {
    /// Each agent's [`View::depth`] (empty in 2D).
    depths: Vec<f64>,
    /// (farthest, nearest) of `depths`, when they differ.
    range: Option<(f64, f64)>,
}

impl DepthCue {
    /// The cue of frame `frame` (none for a 2D scene or a frame of no depth).
    pub(crate) fn of(framer: &Framer<'_>, frame: usize) -> Self {
        if framer.scene().dim != 3 {
            return Self {
                depths: Vec::new(),
                range: None,
            };
        }
        let view = framer.view();
        let depths: Vec<f64> = framer.scene().frames[frame]
            .positions
            .iter()
            .map(|&q| view.depth(q))
            .collect();
        let (far, near) = depths
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &z| {
                (lo.min(z), hi.max(z))
            });
        let range = (near > far).then_some((far, near));
        Self { depths, range }
    }

    /// The depth of agent `i` (0 in 2D).
    fn depth(&self, i: usize) -> f64 {
        self.depths.get(i).copied().unwrap_or(0.0)
    }

    /// The depth of the middle of the edge (i, j).
    fn edge_depth(&self, (i, j): (u32, u32)) -> f64 {
        0.5 * (self.depth(i as usize) + self.depth(j as usize))
    }

    /// Whether the frame is depth-cued.
    fn is_some(&self) -> bool {
        self.range.is_some()
    }

    /// `colour` at depth `depth`: itself at the nearest agent's depth, [`DEPTH_FADE`] of the way
    /// to the background at the farthest's.
    fn fade(&self, colour: [u8; 3], depth: f64) -> [u8; 3] {
        let Some((far, near)) = self.range else {
            return colour;
        };
        let farness = ((near - depth) / (near - far)).clamp(0.0, 1.0);
        style::blend(colour, BACKGROUND, DEPTH_FADE * farness)
    }

    /// `colour` of a body whose nearest point lies at depth `front`: faded fully
    /// ([`DEPTH_FADE`]) when the whole body lies behind the farthest agent, itself otherwise.
    fn fade_behind(&self, colour: [u8; 3], front: f64) -> [u8; 3] {
        match self.range {
            Some((far, _)) if front < far => style::blend(colour, BACKGROUND, DEPTH_FADE),
            _ => colour,
        }
    }
}

/// The smallest agent marker, in pixels.
const MIN_MARKER_PX: f64 = 3.0;
/// The most of the desired distance d an agent's marker spans, so that the edges between
/// neighbours stay visible between their markers in panels that show a wide flock.
const MARKER_PER_SPACING: f64 = 0.4;

/// The length in pixels of an agent's marker: `marker_px`, or less where the desired distance d
/// spans few pixels (`per_pixel` data units a pixel), at least [`MIN_MARKER_PX`].
fn agent_marker_px(marker_px: f64, desired_distance: Option<f64>, per_pixel: f64) -> f64 {
    match desired_distance {
        Some(d) if d > 0.0 && per_pixel > 0.0 => marker_px
            .min(MARKER_PER_SPACING * d / per_pixel)
            .max(MIN_MARKER_PX.min(marker_px)),
        _ => marker_px,
    }
}

/// Each agent's (projected) velocity as an arrow from the agent, the fastest `3 · length` long.
fn draw_velocities<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    framer: &Framer<'_>,
    frame: usize,
    window: Rect,
    length: f64,
) -> Result<(), VizError> {
    let state = &framer.scene().frames[frame];
    let velocities: Vec<DVec2> = state
        .velocities
        .iter()
        .map(|&p| framer.project_vector(p))
        .collect();
    let fastest = velocities
        .iter()
        .map(|v| v.length())
        .filter(|s| s.is_finite())
        .fold(0.0, f64::max);
    if fastest <= 0.0 {
        return Ok(());
    }
    let scale = 3.0 * length / fastest;
    let colour = style::rgb(VELOCITY).stroke_width(1);
    let mut paths = Vec::new();
    for (&q, &v) in state.positions.iter().zip(&velocities) {
        let tail = framer.project(q);
        let tip = tail + v * scale;
        let Some(e) = v.try_normalize() else { continue };
        if !(window.contains(tail) && window.contains(tip)) {
            continue;
        }
        arrow(&mut paths, (tail, tip, e), 0.3 * length, colour);
    }
    chart.draw_series(paths).map_err(VizError::draw)?;
    Ok(())
}

/// An arrow from `tail` to `tip` along the unit vector `e` (pixels), with a head of `head`
/// pixels: its shaft and its two barbs, pushed onto `paths`.
pub(crate) fn arrow(
    paths: &mut Vec<PathElement<(f64, f64)>>,
    (tail, tip, e): (DVec2, DVec2, DVec2),
    head: f64,
    colour: ShapeStyle,
) {
    let back = tip - head * e;
    paths.push(PathElement::new(vec![tuple(tail), tuple(tip)], colour));
    paths.push(PathElement::new(
        vec![
            tuple(back + 0.5 * head * e.perp()),
            tuple(tip),
            tuple(back - 0.5 * head * e.perp()),
        ],
        colour,
    ));
}

/// The periodic box of the scene, if any: the rectangle [0, L₁] × [0, L₂] in 2D, the twelve
/// edges of the cuboid projected in 3D, thin and grey, cut to the window.
fn draw_periodic_box<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    framer: &Framer<'_>,
    window: Rect,
) -> Result<(), VizError> {
    let Some(size) = framer.scene().periodic_box else {
        return Ok(());
    };
    let corner = |k: usize| {
        DVec3::new(
            if k & 1 == 0 { 0.0 } else { size.x },
            if k & 2 == 0 { 0.0 } else { size.y },
            if k & 4 == 0 { 0.0 } else { size.z },
        )
    };
    // the corners joined along one axis: 4 edges in 2D, 12 in 3D
    let corners = if framer.scene().dim == 2 { 4 } else { 8 };
    let mut lines = Vec::new();
    for a in 0..corners {
        for axis in [1, 2, 4] {
            let b = a | axis;
            if b != a && b < corners {
                let (p, q) = (framer.project(corner(a)), framer.project(corner(b)));
                if let Some((p, q)) = clip_segment(p, q, window) {
                    lines.push(PathElement::new(
                        vec![tuple(p), tuple(q)],
                        style::rgb(PERIODIC_BOX).stroke_width(1),
                    ));
                }
            }
        }
    }
    chart.draw_series(lines).map_err(VizError::draw)?;
    Ok(())
}

/// The most dots of one agent's dotted trail.
pub const MAX_TRAIL_DOTS: usize = 60;

/// Trails of the last `panel.trail` frames, of the agents present in all of them, and of the
/// γ-agent: lines, or dots at the recorded positions when `panel.dotted_trails`.
fn draw_trails<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    framer: &Framer<'_>,
    frame: usize,
    panel: &PanelStyle,
    window: Rect,
) -> Result<(), VizError> {
    let scene = framer.scene();
    let range = frame.saturating_sub(panel.trail)..frame + 1;
    let frames = &scene.frames[range.clone()];
    let stride = frames.len().div_ceil(MAX_TRAIL_DOTS).max(1);
    let mut paths = Vec::new();
    let mut dots = Vec::new();
    // each run of a trail: split where the agent crosses the wrap of a periodic box
    let mut add = |runs: Vec<Vec<DVec2>>, colour| {
        if panel.dotted_trails {
            let inside = runs
                .iter()
                .flatten()
                .rev()
                .step_by(stride)
                .filter(|p| window.contains(**p));
            dots.extend(inside.map(|&p| Circle::new(tuple(p), 1, style::rgb(colour).filled())));
            return;
        }
        for points in runs {
            for run in clip_polyline(&points, window) {
                paths.push(PathElement::new(
                    run.into_iter().map(tuple).collect::<Vec<_>>(),
                    style::rgb(colour).stroke_width(1),
                ));
            }
        }
    };
    for i in 0..frames[frames.len() - 1].positions.len() {
        let runs = scene
            .trail_runs(i, range.clone())
            .into_iter()
            .map(|run| run.into_iter().map(|q| framer.project(q)).collect())
            .collect();
        add(runs, TRAIL);
    }
    let gamma: Option<Vec<DVec2>> = frames
        .iter()
        .map(|f| f.gamma.map(|g| framer.project(g)))
        .collect();
    add(gamma.into_iter().collect(), GAMMA);
    chart.draw_series(paths).map_err(VizError::draw)?;
    chart.draw_series(dots).map_err(VizError::draw)?;
    Ok(())
}

/// The α-agents, far ones first (faded by `cue`), as triangles of length `length` (data units)
/// along their (projected) velocity; agents at rest as dots of a quarter of `marker_px` pixels;
/// failed agents as crosses of [`FAILED`] as wide as a triangle is long, below the others.
fn draw_agents<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    framer: &Framer<'_>,
    frame: usize,
    window: Rect,
    length: f64,
    marker_px: f64,
    cue: &DepthCue,
) -> Result<(), VizError> {
    let state = &framer.scene().frames[frame];
    let mut order: Vec<usize> = (0..state.positions.len()).collect();
    if cue.is_some() {
        order.sort_by(|&a, &b| cue.depth(a).total_cmp(&cue.depth(b)).then(a.cmp(&b)));
    }
    let mut triangles = Vec::new();
    let mut dots = Vec::new();
    let mut crosses = Vec::new();
    for i in order {
        let centre = framer.project(state.positions[i]);
        if !window.contains(centre) {
            continue;
        }
        if state.has_failed(i) {
            let stroke = style::rgb(cue.fade(FAILED, cue.depth(i))).stroke_width(2);
            for arm in [DVec2::new(1.0, 1.0), DVec2::new(1.0, -1.0)] {
                let arm = 0.35 * length * arm;
                crosses.push(PathElement::new(
                    vec![tuple(centre - arm), tuple(centre + arm)],
                    stroke,
                ));
            }
            continue;
        }
        let agent = style::rgb(cue.fade(AGENT, cue.depth(i))).filled();
        match framer.project_vector(state.facing(i)).try_normalize() {
            Some(e) => {
                let side = 0.36 * length * e.perp();
                let tip = centre + (2.0 / 3.0) * length * e;
                let back = centre - (1.0 / 3.0) * length * e;
                triangles.push(Polygon::new(
                    vec![tuple(tip), tuple(back + side), tuple(back - side)],
                    agent,
                ));
            }
            None => dots.push(Circle::new(
                tuple(centre),
                (0.25 * marker_px).round().max(1.0) as u32,
                agent,
            )),
        }
    }
    chart.draw_series(crosses).map_err(VizError::draw)?;
    chart.draw_series(triangles).map_err(VizError::draw)?;
    chart.draw_series(dots).map_err(VizError::draw)?;
    Ok(())
}

/// The γ-agent: a red diamond with a dark outline.
fn draw_gamma<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    framer: &Framer<'_>,
    frame: usize,
    window: Rect,
    length: f64,
) -> Result<(), VizError> {
    let Some(gamma) = framer.scene().frames[frame]
        .gamma
        .map(|g| framer.project(g))
    else {
        return Ok(());
    };
    if !window.contains(gamma) {
        return Ok(());
    }
    let r = 0.7 * length;
    let diamond: Vec<(f64, f64)> = [DVec2::X, DVec2::Y, -DVec2::X, -DVec2::Y]
        .into_iter()
        .map(|d| tuple(gamma + r * d))
        .collect();
    let mut outline = diamond.clone();
    outline.push(diamond[0]);
    chart
        .draw_series([Polygon::new(diamond, style::rgb(GAMMA).filled())])
        .map_err(VizError::draw)?;
    chart
        .draw_series([PathElement::new(outline, style::rgb(INK).stroke_width(1))])
        .map_err(VizError::draw)?;
    Ok(())
}
