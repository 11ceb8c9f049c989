//! The colours and sizes of the figures, chosen to read like the papers' black-and-white plots:
//! white background, dark-blue agents, light-grey edges, grey obstacles, a red γ-agent.
//!
//! Every kind of mark has a colour of its own, so the marks of an SVG can be found by colour: an
//! agent is a `<polygon>` (a triangle; a `<circle>` when it does not move) with
//! `fill="#1F4E9C"` ([`hex`]`(`[`AGENT`]`)`), the γ-agent a `<polygon>` with `fill="#D62728"`, a
//! failed agent two `<polyline>`s with `stroke="#C2185B"` ([`FAILED`]).

use plotters::style::RGBColor;

/// The background.
pub const BACKGROUND: [u8; 3] = [0xFF, 0xFF, 0xFF];
/// Text and axes.
pub const INK: [u8; 3] = [0x00, 0x00, 0x00];
/// The α-agents' markers.
pub const AGENT: [u8; 3] = [0x1F, 0x4E, 0x9C];
/// A failed agent's marker, a cross (`conditions.faults`: the trajectory's `failed` column).
pub const FAILED: [u8; 3] = [0xC2, 0x18, 0x5B];
/// The edges of the proximity net.
pub const EDGE: [u8; 3] = [0x96, 0x96, 0x96];
/// An edge of a depth-cued 3D panel at the nearest agent's depth, faded towards the background
/// with depth (the far side of the net is lighter than [`EDGE`]).
pub const NEAR_EDGE: [u8; 3] = [0x40, 0x40, 0x40];
/// An edge under attraction (stress weight s_ij > 0, ‖q_j − q_i‖ > d: j ∈ F_i⁺, ACC 2004 eq. 28).
pub const ATTRACTION: [u8; 3] = [0xE0, 0x82, 0x14];
/// An edge under repulsion (s_ij < 0, ‖q_j − q_i‖ < d: j ∈ F_i⁻).
pub const REPULSION: [u8; 3] = [0x7B, 0x32, 0x94];
/// An agent of zero local stress (S_i = 0, ACC 2004 eq. 31, case ii) in the figure of
/// [`reynolds_svg`](crate::reynolds_svg).
pub const NEUTRAL: [u8; 3] = [0x4D, 0x4D, 0x4D];
/// The motion-planning term u_i^mp of the (α, α) protocol (ACC 2004 eq. 27), an arrow.
pub const MOTION_PLANNING: [u8; 3] = [0xB2, 0x18, 0x2B];
/// The velocity-matching term u_i^vm, and Reynolds's alignment, an arrow.
pub const VELOCITY_MATCHING: [u8; 3] = [0x1B, 0x9E, 0x77];
/// A velocity arrow.
pub const VELOCITY: [u8; 3] = [0x2C, 0xA0, 0x2C];
/// The agents' trails.
pub const TRAIL: [u8; 3] = [0x9D, 0xB9, 0xE0];
/// The sides of a periodic box.
pub const PERIODIC_BOX: [u8; 3] = [0x6E, 0x6E, 0x6E];
/// The obstacles' fill.
pub const OBSTACLE: [u8; 3] = [0xA8, 0xA8, 0xA8];
/// The obstacles' outline.
pub const OBSTACLE_OUTLINE: [u8; 3] = [0x5A, 0x5A, 0x5A];
/// A 3D wall seen face-on (its boundary plane), drawn behind the flock.
pub const WALL_PLANE: [u8; 3] = [0xE8, 0xE8, 0xE8];
/// The γ-agent's marker and path.
pub const GAMMA: [u8; 3] = [0xD6, 0x27, 0x28];
/// Metric curves.
pub const CURVE: [u8; 3] = [0x1F, 0x4E, 0x9C];
/// Secondary metric curves (C* beside C).
pub const CURVE_SECONDARY: [u8; 3] = [0x8C, 0x8C, 0x8C];
/// Light grid lines of the metric panels.
pub const GRID: [u8; 3] = [0xE6, 0xE6, 0xE6];

/// A colour as SVG writes it, e.g. `#1F4E9C`.
///
/// # Example
/// ```
/// assert_eq!(flock_viz::style::hex(flock_viz::style::AGENT), "#1F4E9C");
/// ```
#[must_use]
pub fn hex(colour: [u8; 3]) -> String {
    format!("#{:02X}{:02X}{:02X}", colour[0], colour[1], colour[2])
}

/// `colour` moved a fraction `amount` (0 to 1) of the way to `toward`, each channel rounded.
///
/// # Example
/// ```
/// use flock_viz::style::{AGENT, BACKGROUND, blend};
///
/// assert_eq!(blend(AGENT, BACKGROUND, 0.0), AGENT);
/// assert_eq!(blend(AGENT, BACKGROUND, 1.0), BACKGROUND);
/// assert_eq!(blend([0, 0, 0], [255, 255, 255], 0.5), [128, 128, 128]);
/// ```
#[must_use]
pub fn blend(colour: [u8; 3], toward: [u8; 3], amount: f64) -> [u8; 3] {
    let amount = amount.clamp(0.0, 1.0);
    std::array::from_fn(|k| {
        let (a, b) = (f64::from(colour[k]), f64::from(toward[k]));
        (a + amount * (b - a)).round() as u8
    })
}

/// The plotters colour.
pub(crate) fn rgb(colour: [u8; 3]) -> RGBColor {
    RGBColor(colour[0], colour[1], colour[2])
}
