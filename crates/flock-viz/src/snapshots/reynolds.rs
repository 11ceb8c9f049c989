//! ACC 2004's reading of the (α, α) protocol as Reynolds's three rules (Olfati-Saber, *A unified
//! analytical look at Reynolds flocking rules*, seed 000 § 4), drawn at one frame of a run: two
//! panels side by side.
//!
//! - Left, the protocol: each agent's motion-planning term u_i^mp = Σ_j s_ij (q_j − q_i) (eq. 27)
//!   and velocity-matching term u_i^vm = c_d Σ_j (p_j − p_i) as arrows ([`MOTION_PLANNING`],
//!   [`VELOCITY_MATCHING`]), on one scale (both are accelerations); each agent a dot coloured by
//!   the sign of its local stress S_i (eq. 31–33): [`ATTRACTION`] when S_i > 0 (pulled towards the
//!   centre of its neighbours), [`REPULSION`] when S_i < 0 (pushed away), [`NEUTRAL`] when S_i = 0
//!   ([`NEUTRAL_STRESS`]).
//! - Right, Reynolds's rules for the same state ([`ReynoldsRules`]): cohesion ([`ATTRACTION`]),
//!   separation ([`REPULSION`]) and alignment ([`VELOCITY_MATCHING`]), each rule on its own scale
//!   (they have different units).
//!
//! In each panel the longest arrow of a scale is d_α long; the net's edges are drawn thin and grey.
//!
//! - [`reynolds_svg`], [`reynolds_png`]: the figure; [`ReynoldsOptions`] its size and frame.

use flocking::graph::ProximityNet;
use flocking::protocols::{
    AgentReading, AlphaAlpha, NEUTRAL_STRESS, ReynoldsRules, StressRegime, Swarm,
};
use glam::{DVec2, DVec3};
use plotters::coord::Shift;
use plotters::element::Text;
use plotters::prelude::{Circle, DrawingArea, DrawingBackend, Rectangle};
use plotters::style::Color;

use crate::draw::format;
use crate::draw::geometry::Rect;
use crate::draw::render::{self, Figure};
use crate::draw::style::{
    self, ATTRACTION, EDGE, MOTION_PLANNING, NEUTRAL, REPULSION, VELOCITY_MATCHING,
};
use crate::error::VizError;
use crate::scene::frames::Scene;
use crate::scene::framing::{Framer, Framing};
use crate::scene::projection::View;
use crate::snapshots::snapshot::{
    Chart, DepthCue, arrow, below_title, draw_edges, grid_size, panel_chart, text_style, tuple,
};

/// How the figure is drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct ReynoldsOptions {
    /// The size of one of the two panels in pixels (width, height).
    pub panel_size: (u32, u32),
    /// The projection of a 3D run (2D runs are drawn in their plane).
    pub view: View,
    /// The scenario's unit of length, for the axis labels.
    pub length_unit: String,
}

impl Default for ReynoldsOptions {
    fn default() -> Self {
        Self {
            panel_size: (640, 640),
            view: View::default(),
            length_unit: "m".to_owned(),
        }
    }
}

/// The figure of frame `frame` of `scene`, read with the (α, α) protocol `alpha` (its net at
/// r = `alpha`'s range), as an SVG document.
///
/// # Errors
/// [`VizError::Invalid`] when the scene cannot be drawn or `frame` is out of range.
///
/// # Example
/// ```
/// use flock_viz::{Frame, ReynoldsOptions, Scene, reynolds_svg};
/// use flocking::protocols::{AlphaAlpha, AlphaAlphaForm, AlphaAlphaParams};
/// use glam::DVec2;
///
/// let alpha = AlphaAlpha::new(AlphaAlphaParams::default(), AlphaAlphaForm::Smooth, 1.0);
/// let q = [DVec2::ZERO, DVec2::new(5.0, 0.0), DVec2::new(0.0, 7.3)];
/// let p = [DVec2::X, DVec2::Y, DVec2::ZERO];
/// let scene = Scene::new(2, 8.4).with_frame(Frame::from_vectors(0.0, &q, &p));
/// let svg = reynolds_svg(&scene, 0, &alpha, &ReynoldsOptions::default()).unwrap();
/// assert!(svg.contains("S_i &lt; 0: away from the centre (2)"));
/// ```
pub fn reynolds_svg(
    scene: &Scene,
    frame: usize,
    alpha: &AlphaAlpha,
    options: &ReynoldsOptions,
) -> Result<String, VizError> {
    render::svg(&ReynoldsFigure::new(scene, frame, alpha, options)?)
}

/// The figure of [`reynolds_svg`] as a PNG image.
///
/// # Errors
/// As [`reynolds_svg`]; [`VizError::Encode`] if PNG encoding fails.
pub fn reynolds_png(
    scene: &Scene,
    frame: usize,
    alpha: &AlphaAlpha,
    options: &ReynoldsOptions,
) -> Result<Vec<u8>, VizError> {
    render::png(&ReynoldsFigure::new(scene, frame, alpha, options)?)
}

/// The figure, its readings computed.
struct ReynoldsFigure<'a> {
    scene: &'a Scene,
    frame: usize,
    options: &'a ReynoldsOptions,
    readings: Vec<AgentReading<DVec3>>,
    d_alpha: f64,
}

impl<'a> ReynoldsFigure<'a> {
    fn new(
        scene: &'a Scene,
        frame: usize,
        alpha: &AlphaAlpha,
        options: &'a ReynoldsOptions,
    ) -> Result<Self, VizError> {
        scene.validate()?;
        let Some(state) = scene.frames.get(frame) else {
            return Err(VizError::invalid(format!(
                "frame {frame} chosen, but the scene has {} frames",
                scene.frames.len()
            )));
        };
        // a 2D state lifted to z = 0 gives the 2D readings, lifted
        let swarm = Swarm::new(state.positions.clone(), state.velocities.clone());
        let net = ProximityNet::brute_force(&swarm.positions, alpha.params().r);
        Ok(Self {
            scene,
            frame,
            options,
            readings: alpha.reynolds_readings(&swarm, &net),
            d_alpha: alpha.params().d_alpha,
        })
    }

    fn title(&self) -> String {
        let t = format::number(self.scene.frames[self.frame].t, 2);
        let name = if self.scene.title.is_empty() {
            String::new()
        } else {
            format!("{}: ", self.scene.title)
        };
        format!("{name}the (α, α) protocol as Reynolds's rules (ACC 2004 § 4), t = {t} s")
    }

    fn count(&self, regime: StressRegime) -> usize {
        self.readings.iter().filter(|r| r.regime == regime).count()
    }
}

impl Figure for ReynoldsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        grid_size(self.options.panel_size, 2, 1, &self.title())
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), VizError> {
        let body = below_title(root, &self.title())?;
        let panels = body.split_evenly((1, 2));
        let framer = Framer::new(self.scene, self.options.view, 0);
        let unit = self.options.length_unit.as_str();
        let protocol_title = "u_i = u_i^mp + u_i^vm (eq. 25, 27)";
        panel_chart(
            &panels[0],
            &framer,
            self.frame,
            (Framing::Flock, unit),
            protocol_title,
            |chart, window, per_pixel| {
                let tolerance = format!("{NEUTRAL_STRESS:e}");
                let legend = [
                    ("motion planning u_i^mp".to_owned(), MOTION_PLANNING),
                    ("velocity matching u_i^vm".to_owned(), VELOCITY_MATCHING),
                    (
                        format!(
                            "S_i > 0: towards the centre ({})",
                            self.count(StressRegime::Towards)
                        ),
                        ATTRACTION,
                    ),
                    (
                        format!(
                            "S_i < 0: away from the centre ({})",
                            self.count(StressRegime::Away)
                        ),
                        REPULSION,
                    ),
                    (
                        format!(
                            "S_i = 0 (to {tolerance}): neutral ({})",
                            self.count(StressRegime::Neutral)
                        ),
                        NEUTRAL,
                    ),
                ];
                let terms: Vec<[(DVec3, [u8; 3]); 2]> = self
                    .readings
                    .iter()
                    .map(|r| {
                        [
                            (r.motion_planning, MOTION_PLANNING),
                            (r.velocity_matching, VELOCITY_MATCHING),
                        ]
                    })
                    .collect();
                let colours: Vec<[u8; 3]> = self
                    .readings
                    .iter()
                    .map(|r| match r.regime {
                        StressRegime::Towards => ATTRACTION,
                        StressRegime::Away => REPULSION,
                        StressRegime::Neutral => NEUTRAL,
                    })
                    .collect();
                let marks = Marks {
                    framer: &framer,
                    frame: self.frame,
                    window,
                    per_pixel,
                    d_alpha: self.d_alpha,
                };
                marks.edges(chart)?;
                marks.arrows(chart, &terms, true)?;
                marks.agents(chart, &colours)?;
                marks.legend(chart, &legend)
            },
        )?;
        let rules_title = "Reynolds's rules: cohesion, separation, alignment";
        panel_chart(
            &panels[1],
            &framer,
            self.frame,
            (Framing::Flock, unit),
            rules_title,
            |chart, window, per_pixel| {
                let legend = [
                    ("cohesion: mean q_j − q_i".to_owned(), ATTRACTION),
                    (
                        format!(
                            "separation: −mean (q_j − q_i), ‖q_j − q_i‖ < d = {}",
                            self.d_alpha
                        ),
                        REPULSION,
                    ),
                    ("alignment: mean p_j − p_i".to_owned(), VELOCITY_MATCHING),
                    ("(each rule on its own scale)".to_owned(), style::INK),
                ];
                let rules: Vec<[(DVec3, [u8; 3]); 3]> = self
                    .readings
                    .iter()
                    .map(|r| {
                        let ReynoldsRules {
                            cohesion,
                            separation,
                            alignment,
                        } = r.rules;
                        [
                            (cohesion, ATTRACTION),
                            (separation, REPULSION),
                            (alignment, VELOCITY_MATCHING),
                        ]
                    })
                    .collect();
                let marks = Marks {
                    framer: &framer,
                    frame: self.frame,
                    window,
                    per_pixel,
                    d_alpha: self.d_alpha,
                };
                marks.edges(chart)?;
                marks.arrows(chart, &rules, false)?;
                marks.agents(chart, &vec![style::AGENT; self.readings.len()])?;
                marks.legend(chart, &legend)
            },
        )
    }
}

/// What a panel's marks need: where they go and how big a pixel is.
struct Marks<'a> {
    framer: &'a Framer<'a>,
    frame: usize,
    window: Rect,
    per_pixel: f64,
    d_alpha: f64,
}

impl Marks<'_> {
    /// The net's edges, thin and grey.
    fn edges<DB: DrawingBackend>(&self, chart: &mut Chart<'_, DB>) -> Result<(), VizError> {
        let cue = DepthCue::of(self.framer, self.frame);
        draw_edges(chart, self.framer, self.frame, self.window, None, &cue)
    }

    /// Per agent its `K` vectors as arrows from the agent, coloured; on one scale for all kinds when
    /// `shared`, else one per kind; the longest of a scale d_α long.
    fn arrows<DB: DrawingBackend, const K: usize>(
        &self,
        chart: &mut Chart<'_, DB>,
        vectors: &[[(DVec3, [u8; 3]); K]],
        shared: bool,
    ) -> Result<(), VizError> {
        let positions = &self.framer.scene().frames[self.frame].positions;
        let projected: Vec<[DVec2; K]> = vectors
            .iter()
            .map(|kinds| std::array::from_fn(|k| self.framer.project_vector(kinds[k].0)))
            .collect();
        let longest = |k: usize| {
            projected
                .iter()
                .map(|v| v[k].length())
                .filter(|l| l.is_finite())
                .fold(0.0, f64::max)
        };
        let mut scales: [f64; K] = std::array::from_fn(longest);
        if shared {
            let all = scales.iter().copied().fold(0.0, f64::max);
            scales = [all; K];
        }
        let head = 5.0 * self.per_pixel;
        let mut paths = Vec::new();
        for k in 0..K {
            if scales[k] <= 0.0 {
                continue;
            }
            let scale = self.d_alpha / scales[k];
            for ((&q, v), kinds) in positions.iter().zip(&projected).zip(vectors) {
                let colour = style::rgb(kinds[k].1).stroke_width(2);
                let tail = self.framer.project(q);
                let tip = tail + v[k] * scale;
                let Some(e) = v[k].try_normalize() else {
                    continue;
                };
                if !(self.window.contains(tail) && self.window.contains(tip)) {
                    continue;
                }
                let head = head.min(0.5 * (tip - tail).length());
                arrow(&mut paths, (tail, tip, e), head, colour);
            }
        }
        chart.draw_series(paths).map_err(VizError::draw)?;
        Ok(())
    }

    /// Each agent as a dot of its colour.
    fn agents<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<'_, DB>,
        colours: &[[u8; 3]],
    ) -> Result<(), VizError> {
        let positions = &self.framer.scene().frames[self.frame].positions;
        let dots: Vec<Circle<(f64, f64), u32>> = positions
            .iter()
            .zip(colours)
            .map(|(&q, &colour)| (self.framer.project(q), colour))
            .filter(|(centre, _)| self.window.contains(*centre))
            .map(|(centre, colour)| Circle::new(tuple(centre), 4, style::rgb(colour).filled()))
            .collect();
        chart.draw_series(dots).map_err(VizError::draw)?;
        Ok(())
    }

    /// The legend, one coloured line per entry, at the top left of the window.
    fn legend<DB: DrawingBackend>(
        &self,
        chart: &mut Chart<'_, DB>,
        entries: &[(String, [u8; 3])],
    ) -> Result<(), VizError> {
        let left = self.window.min.x + 8.0 * self.per_pixel;
        // a white box behind the lines, so that the flock does not hide them
        let widest = entries
            .iter()
            .map(|(label, _)| label.chars().count())
            .max()
            .unwrap_or(0) as f64;
        let (width, height) = (
            (12.0 + 7.0 * widest) * self.per_pixel,
            (8.0 + 17.0 * entries.len() as f64) * self.per_pixel,
        );
        let (lo, hi) = (
            (
                self.window.min.x + 2.0 * self.per_pixel,
                self.window.max.y - height,
            ),
            (
                (self.window.min.x + width).min(self.window.max.x),
                self.window.max.y - 2.0 * self.per_pixel,
            ),
        );
        chart
            .draw_series([
                Rectangle::new([lo, hi], style::rgb(style::BACKGROUND).filled()),
                Rectangle::new([lo, hi], style::rgb(EDGE).stroke_width(1)),
            ])
            .map_err(VizError::draw)?;
        for (k, (label, colour)) in entries.iter().enumerate() {
            let top = self.window.max.y - (6.0 + 17.0 * k as f64) * self.per_pixel;
            let ink = style::rgb(*colour);
            chart
                .draw_series([Text::new(
                    label.clone(),
                    (left, top),
                    text_style(13).color(&ink),
                )])
                .map_err(VizError::draw)?;
        }
        Ok(())
    }
}
