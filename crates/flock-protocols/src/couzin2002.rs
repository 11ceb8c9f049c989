//! The zone model of Couzin, Krause, James, Ruxton and Franks ("Collective memory and spatial
//! sorting in animal groups", J. theor. Biol. 218, 1–11, 2002): repulsion, orientation and
//! attraction in three nested zones, a blind angle behind each individual, a bounded turning rate
//! and angular noise.

use flock_graph::ProximityNet;
use flock_math::parallel::fill_interruptible;
use flock_math::{Domain, Vector};

use crate::error::{ParamError, check};
use crate::swarm::heading_mismatch;
use crate::{LocalForm, Perceived, Protocol, Swarm, Update};
use flock_math::stream::{Purpose, Streams};

/// The parameters of the zone model, named as the paper names them. Defaults: r_r = 1,
/// α = 270°, θ = 40° s⁻¹, s = 3 units s⁻¹, σ = 0.05 rad (with τ = 0.1 s, the scenario's step);
/// r_r, α, θ, s and τ are as public reimplementations set them (jiwy2020's `main.m`,
/// couzinswarm's `sandbox/torus.py`), σ is not confirmed (the paper itself was not available to
/// this work). Δr_o and Δr_a are
/// the paper's two axes (0–15 in its Fig. 2). The two readings of the rule that the sources
/// leave open are [`Blend`] and [`BlindCone`] (docs/models.md compares each with the paper's
/// Fig. 2). A scenario gives Δr_o and Δr_a; the others default to [`CouzinParams::default`]'s.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct CouzinParams {
    /// The radius r_r > 0 of the zone of repulsion.
    #[cfg_attr(feature = "serde", serde(default = "CouzinParams::default_r_r"))]
    pub r_r: f64,
    /// The width Δr_o ≥ 0 of the zone of orientation (r_o = r_r + Δr_o).
    pub delta_r_o: f64,
    /// The width Δr_a ≥ 0 of the zone of attraction (r_a = r_o + Δr_a).
    pub delta_r_a: f64,
    /// The field of perception α (degrees, (0, 360]): neighbours in the blind cone behind,
    /// 360° − α wide, are not seen.
    #[cfg_attr(
        feature = "serde",
        serde(default = "CouzinParams::default_field_of_perception")
    )]
    pub field_of_perception: f64,
    /// The largest turning rate θ (degrees per second).
    #[cfg_attr(
        feature = "serde",
        serde(default = "CouzinParams::default_turning_rate")
    )]
    pub turning_rate: f64,
    /// The speed s > 0.
    #[cfg_attr(feature = "serde", serde(default = "CouzinParams::default_speed"))]
    pub speed: f64,
    /// The standard deviation σ (rad) of the angular noise on the desired direction.
    #[cfg_attr(feature = "serde", serde(default = "CouzinParams::default_noise"))]
    pub noise: f64,
    /// How the orientation and attraction sums are combined when both zones hold neighbours.
    #[cfg_attr(feature = "serde", serde(default))]
    pub blend: Blend,
    /// Which zones the blind cone hides neighbours from.
    #[cfg_attr(feature = "serde", serde(default))]
    pub blind_cone: BlindCone,
}

/// How d_o and d_a are combined when both the zone of orientation and that of attraction hold
/// neighbours (Couzin et al. 2002, eq. 2–3 and the rule after them).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Blend {
    /// d = ½ (d̂_o + d̂_a): each sum normalised first, so that the two zones weigh the same
    /// whatever their numbers of neighbours.
    #[default]
    Unit,
    /// d = ½ (d_o + d_a): the raw sums, as the rule is written and the public reimplementations
    /// compute it, so that the zone with more neighbours weighs more.
    Raw,
}

/// Which neighbours the blind cone behind an individual (360° − α wide) hides.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BlindCone {
    /// Those of every zone, the zone of repulsion included.
    #[default]
    Everywhere,
    /// Those of the zones of orientation and attraction only: a neighbour in the zone of
    /// repulsion is always avoided.
    BeyondRepulsion,
}

/// The collective states of Couzin et al. (2002, Fig. 1(b)–(e)), named from the group's
/// polarisation p_group and angular momentum m_group by the thresholds of [`CollectiveState::of`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CollectiveState {
    /// Low polarisation and low angular momentum: a cohesive, disordered group.
    Swarm,
    /// Individuals circling an empty core: m_group ≥ [`CollectiveState::TORUS`].
    Torus,
    /// Aligned but moving within the group: [`CollectiveState::PARALLEL`] ≤ p_group <
    /// [`CollectiveState::HIGHLY_PARALLEL`].
    DynamicParallel,
    /// Aligned and rigid: p_group ≥ [`CollectiveState::HIGHLY_PARALLEL`].
    HighlyParallel,
}

impl CollectiveState {
    /// The least angular momentum m_group of a torus.
    pub const TORUS: f64 = 0.5;
    /// The least polarisation p_group of a parallel group.
    pub const PARALLEL: f64 = 0.5;
    /// The least polarisation p_group of a highly parallel group.
    pub const HIGHLY_PARALLEL: f64 = 0.95;

    /// The state of a group with polarisation `p` and angular momentum `m` (means over the
    /// settled run): a torus when m ≥ 0.5, else highly parallel when p ≥ 0.95, dynamic parallel
    /// when p ≥ 0.5, a swarm otherwise. The paper draws its states from both measures without
    /// numerical borders; these are ours.
    ///
    /// # Example
    /// ```
    /// use flock_protocols::couzin2002::CollectiveState;
    ///
    /// assert_eq!(CollectiveState::of(0.1, 0.9), CollectiveState::Torus);
    /// assert_eq!(CollectiveState::of(0.99, 0.1), CollectiveState::HighlyParallel);
    /// assert_eq!(CollectiveState::of(0.7, 0.2), CollectiveState::DynamicParallel);
    /// assert_eq!(CollectiveState::of(0.2, 0.1), CollectiveState::Swarm);
    /// ```
    #[must_use]
    pub fn of(p: f64, m: f64) -> Self {
        if m >= Self::TORUS {
            Self::Torus
        } else if p >= Self::HIGHLY_PARALLEL {
            Self::HighlyParallel
        } else if p >= Self::PARALLEL {
            Self::DynamicParallel
        } else {
            Self::Swarm
        }
    }

    /// The state's name as the paper writes it ("dynamic parallel").
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Swarm => "swarm",
            Self::Torus => "torus",
            Self::DynamicParallel => "dynamic parallel",
            Self::HighlyParallel => "highly parallel",
        }
    }
}

impl Default for CouzinParams {
    fn default() -> Self {
        Self {
            r_r: 1.0,
            delta_r_o: 2.0,
            delta_r_a: 12.0,
            field_of_perception: 270.0,
            turning_rate: 40.0,
            speed: 3.0,
            noise: 0.05,
            blend: Blend::default(),
            blind_cone: BlindCone::default(),
        }
    }
}

// The defaults of a scenario that leaves them out: [`CouzinParams::default`]'s.
#[cfg(feature = "serde")]
impl CouzinParams {
    fn default_r_r() -> f64 {
        Self::default().r_r
    }

    fn default_field_of_perception() -> f64 {
        Self::default().field_of_perception
    }

    fn default_turning_rate() -> f64 {
        Self::default().turning_rate
    }

    fn default_speed() -> f64 {
        Self::default().speed
    }

    fn default_noise() -> f64 {
        Self::default().noise
    }
}

/// The desired direction d_i of Couzin et al. (2002, eq. 1–3), then noise and a bounded turn.
///
/// With r_ij = q_j − q_i (the minimum image on a torus) and the neighbours j that i sees (outside
/// its blind cone: the angle between its heading and r_ij at most α/2):
/// - if any is in the zone of repulsion (‖r_ij‖ < r_r): d = −Σ r_ij / ‖r_ij‖ over them (eq. 1);
/// - otherwise d_o = Σ v_j / ‖v_j‖ over the zone of orientation (r_r ≤ ‖r_ij‖ < r_o, eq. 2) and
///   d_a = Σ r_ij / ‖r_ij‖ over the zone of attraction (r_o ≤ ‖r_ij‖ < r_a, eq. 3); d is
///   ½ (d̂_o + d̂_a) ([`Blend::Unit`]) or ½ (d_o + d_a) ([`Blend::Raw`]) when both zones hold
///   neighbours, the one that does otherwise, and the present heading when neither does. The
///   sums run over the neighbours only, i left out.
///
/// With [`BlindCone::BeyondRepulsion`] a neighbour in the zone of repulsion is seen wherever it
/// is; with [`BlindCone::Everywhere`] the cone hides it too.
///
/// d is turned by an angle drawn from N(0, σ²) (in 3D about a random axis perpendicular to it;
/// keyed draws, [`Purpose::ModelNoise`]), then the heading turns towards it by at most θ τ (the
/// whole way when the angle is smaller), and the individual moves s τ along its new heading
/// ([`Update::TurnThenMove`]).
///
/// The paper's group measures are the polarisation p_group = ‖Σ v̂_i‖ / N and the angular
/// momentum m_group = ‖Σ r̂_ic × v̂_i‖ / N about the group's centre (the `polarisation` and
/// `milling` metrics).
#[derive(Clone, Debug, PartialEq)]
pub struct Couzin<V> {
    params: CouzinParams,
    step: f64,
    streams: Streams,
    domain: Domain<V>,
}

impl<V: Vector> Couzin<V> {
    /// The model with step `step` (the paper's τ), its noise drawn from the streams of `seed`,
    /// in `domain` (the paper's: open space).
    ///
    /// # Errors
    /// A parameter outside its domain, named as in [`CouzinParams`].
    pub fn new(
        params: CouzinParams,
        step: f64,
        seed: u64,
        domain: Domain<V>,
    ) -> Result<Self, ParamError> {
        check::positive("r_r", params.r_r)?;
        check::non_negative("delta_r_o", params.delta_r_o)?;
        check::non_negative("delta_r_a", params.delta_r_a)?;
        check::positive("field_of_perception", params.field_of_perception)?;
        check::require(
            params.field_of_perception <= 360.0,
            "field_of_perception",
            params.field_of_perception,
            "is above 360 degrees",
            "give the field of perception in degrees, at most 360 (no blind cone)",
        )?;
        check::positive("turning_rate", params.turning_rate)?;
        check::positive("speed", params.speed)?;
        check::non_negative("noise", params.noise)?;
        check::positive("step", step)?;
        Ok(Self {
            params,
            step,
            streams: Streams::new(seed),
            domain,
        })
    }

    /// The outer radius r_a = r_r + Δr_o + Δr_a.
    #[must_use]
    pub fn attraction_radius(&self) -> f64 {
        self.params.r_r + self.params.delta_r_o + self.params.delta_r_a
    }

    /// The new velocity of agent `i` at `q` with velocity `p` from its candidates `others`
    /// (position, velocity) at time `t`.
    fn turn(&self, i: u32, t: f64, q: V, p: V, others: impl Iterator<Item = (V, V)>) -> V {
        let c = &self.params;
        let heading = p.normalize_or_zero();
        let (r_o, r_a) = (c.r_r + c.delta_r_o, self.attraction_radius());
        let cos_half = (c.field_of_perception.to_radians() / 2.0).cos();
        let blind = c.field_of_perception < 360.0;
        let (mut repel, mut orient, mut attract) = (V::ZERO, V::ZERO, V::ZERO);
        let (mut n_r, mut n_o, mut n_a) = (0u32, 0u32, 0u32);
        for (qj, pj) in others {
            let r = self.domain.displacement(q, qj);
            let d = r.length();
            if d >= r_a || d == 0.0 {
                continue;
            }
            let unit = r / d;
            let hidden = blind && heading != V::ZERO && heading.dot(unit) < cos_half;
            if hidden && (d >= c.r_r || c.blind_cone == BlindCone::Everywhere) {
                continue;
            }
            if d < c.r_r {
                repel -= unit;
                n_r += 1;
            } else if d < r_o {
                orient += pj.normalize_or_zero();
                n_o += 1;
            } else {
                attract += unit;
                n_a += 1;
            }
        }
        let desired = if n_r > 0 {
            repel
        } else {
            match (n_o > 0, n_a > 0) {
                (true, true) => match c.blend {
                    Blend::Unit => (orient.normalize_or_zero() + attract.normalize_or_zero()) * 0.5,
                    Blend::Raw => (orient + attract) * 0.5,
                },
                (true, false) => orient,
                (false, true) => attract,
                (false, false) => heading,
            }
        }
        .normalize_or_zero();
        let desired = if desired == V::ZERO {
            heading
        } else {
            self.perturb(i, t, desired)
        };
        bounded_turn(heading, desired, c.turning_rate.to_radians() * self.step) * c.speed
    }

    /// `d` (a unit vector) turned by an angle from N(0, σ²) towards a random perpendicular.
    fn perturb(&self, i: u32, t: f64, d: V) -> V {
        if self.params.noise == 0.0 {
            return d;
        }
        let k = (t / self.step).round() as u64;
        let mut draws = self.streams.draws(Purpose::ModelNoise, u64::from(i), k);
        let angle = self.params.noise * draws.normal();
        let g: V = draws.normal_vector();
        let w = (g - d * g.dot(d)).normalize_or_zero();
        let (sin, cos) = angle.sin_cos();
        d * cos + w * sin
    }
}

/// The unit vector `from` turned towards the unit vector `to` by at most `max_angle` radians, in
/// the plane they span (`to` itself when nearer; `to` when `from` is zero).
#[must_use]
pub fn bounded_turn<V: Vector>(from: V, to: V, max_angle: f64) -> V {
    if from == V::ZERO {
        return to;
    }
    let angle = from.dot(to).clamp(-1.0, 1.0).acos();
    if angle <= max_angle {
        return to;
    }
    // the unit vector in the plane of `from` and `to`, perpendicular to `from`
    let across = (to - from * from.dot(to)).normalize_or_zero();
    let across = if across == V::ZERO {
        // opposite directions: any perpendicular; the first axis not along `from`
        let axis = V::from_fn(|k| {
            if k == usize::from(from.coord(0).abs() > 0.9) {
                1.0
            } else {
                0.0
            }
        });
        (axis - from * from.dot(axis)).normalize_or_zero()
    } else {
        across
    };
    let (sin, cos) = max_angle.sin_cos();
    from * cos + across * sin
}

impl<V: Vector> Protocol<V> for Couzin<V> {
    fn interaction_range(&self) -> f64 {
        self.attraction_radius()
    }

    fn uses_net_distances(&self) -> bool {
        false
    }

    fn controls(&self, t: f64, swarm: &Swarm<V>, net: &ProximityNet, inputs: &mut [V]) {
        let (q, p) = (&swarm.positions, &swarm.velocities);
        let numbering = net.numbering();
        fill_interruptible(inputs, |i| {
            let others = net
                .graph()
                .neighbours(i)
                .iter()
                .map(|&j| (q[j as usize], p[j as usize]));
            self.turn(numbering.original(i) as u32, t, q[i], p[i], others)
        });
    }

    /// The zones' sums run over each individual's list in ascending original index and the
    /// noise is keyed by original index: individuals at random are stored by cell.
    fn follows_numbering(&self) -> bool {
        true
    }

    /// The heading mismatch n − ‖Σ_i p̂_i‖ (p̂_i = p_i/‖p_i‖): the model decreases no
    /// energy.
    fn energy(&self, _t: f64, swarm: &Swarm<V>, net: &ProximityNet) -> f64 {
        heading_mismatch(&swarm.velocities, net.numbering())
    }

    fn update(&self) -> Update {
        Update::TurnThenMove
    }

    fn measures_in_domain(&self) -> bool {
        true
    }

    fn local_form(&self) -> Option<&dyn LocalForm<V>> {
        Some(self)
    }
}

impl<V: Vector> LocalForm<V> for Couzin<V> {
    fn local_input(&self, t: f64, own: &Perceived<V>, heard: &[Perceived<V>]) -> V {
        let others = heard.iter().map(|o| (o.position, o.velocity));
        self.turn(own.agent, t, own.position, own.velocity, others)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;
    use glam::{DVec2, DVec3};

    /// A model without noise or turning bound, in open 2D space, with `blend` and `blind_cone`.
    fn reading(blend: Blend, blind_cone: BlindCone) -> Couzin<DVec2> {
        let params = CouzinParams {
            noise: 0.0,
            turning_rate: 1e6,
            blend,
            blind_cone,
            ..CouzinParams::default()
        };
        Couzin::new(params, 0.1, 1, Domain::Open).unwrap()
    }

    /// One neighbour in the zone of orientation heading along y and three in the zone of
    /// attraction along x: normalised first, the two zones weigh alike (d along (1, 1)); raw,
    /// the three attractions outweigh the one heading (d along (3, 1)).
    #[test]
    fn the_blends_weigh_the_zones_as_their_definitions_say() {
        let others = [
            (DVec2::new(0.0, 2.0), DVec2::new(0.0, 3.0)),
            (DVec2::new(10.0, 0.0), DVec2::new(3.0, 0.0)),
            (DVec2::new(11.0, 0.0), DVec2::new(3.0, 0.0)),
            (DVec2::new(12.0, 0.0), DVec2::new(3.0, 0.0)),
        ];
        let (q, p) = (DVec2::ZERO, DVec2::new(3.0, 0.0));
        let turned = |blend| {
            reading(blend, BlindCone::Everywhere)
                .turn(0, 0.0, q, p, others.into_iter())
                .normalize()
        };
        assert_abs_diff_eq!(
            turned(Blend::Unit),
            DVec2::new(1.0, 1.0).normalize(),
            epsilon = 1e-12
        );
        assert_abs_diff_eq!(
            turned(Blend::Raw),
            DVec2::new(3.0, 1.0).normalize(),
            epsilon = 1e-12
        );
    }

    /// A neighbour right behind, within r_r: hidden by the cone that covers every zone (the
    /// heading is kept), avoided when the zone of repulsion sees all round (the individual turns
    /// away, forwards).
    #[test]
    fn the_blind_cone_hides_the_zone_of_repulsion_only_when_it_covers_every_zone() {
        let behind = [(DVec2::new(-0.5, 0.1), DVec2::new(3.0, 0.0))];
        let (q, p) = (DVec2::ZERO, DVec2::new(3.0, 0.0));
        let turned = |cone| {
            reading(Blend::Unit, cone)
                .turn(0, 0.0, q, p, behind.into_iter())
                .normalize()
        };
        assert_abs_diff_eq!(turned(BlindCone::Everywhere), DVec2::X, epsilon = 1e-12);
        assert_abs_diff_eq!(
            turned(BlindCone::BeyondRepulsion),
            DVec2::new(0.5, -0.1).normalize(),
            epsilon = 1e-12
        );
    }

    #[test]
    fn a_turn_is_bounded_by_the_rate() {
        let turned = bounded_turn(DVec2::X, DVec2::Y, 0.1);
        assert_abs_diff_eq!(turned.length(), 1.0, epsilon = 1e-15);
        assert_abs_diff_eq!(turned.dot(DVec2::X).acos(), 0.1, epsilon = 1e-12);
        assert!(turned.y > 0.0);
        // within the bound, the whole way
        assert_eq!(
            bounded_turn(DVec2::X, DVec2::new(0.1, 1.0).normalize(), 2.0),
            DVec2::new(0.1, 1.0).normalize()
        );
        // opposite directions in 3D: still a unit vector turned by the bound
        let back = bounded_turn(DVec3::X, -DVec3::X, 0.2);
        assert_abs_diff_eq!(back.length(), 1.0, epsilon = 1e-15);
        assert_abs_diff_eq!(back.dot(DVec3::X).acos(), 0.2, epsilon = 1e-12);
    }
}
