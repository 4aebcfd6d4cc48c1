//! Phonon packets: initial perturbations of a block of particles (seed figs. 2.17–2.18).
//!
//! The seed gives "an initial perturbation … to the middle 16 elements" of a 128-element
//! lattice but not its shape. ltikit's packet is a displacement, released from rest:
//!
//! ```text
//! qₙ(0) = A · w(j) · cos(k₀a · j),   j = n − n₁ = 0 … W−1 over the block,   q̇(0) = 0,
//! ```
//!
//! with the carrier k₀a = π for a **zone-edge** packet (neighbours in antiphase, group
//! velocity aω0 cos(k₀a/2) = 0) and k₀a = 0 for a **zone-centre** packet (all in phase,
//! group velocity aω0, the speed of sound). The envelope w is either
//!
//! - [`Envelope::Hann`], w(j) = sin²(π(j + 1)/(W + 1)), vanishing just outside the block —
//!   the default: its energy sits within about ±2π/W of k₀, so the packets are what their
//!   names say;
//! - [`Envelope::Rectangular`], w = 1. Its zone-centre version is a plateau whose strain is
//!   all at the two ends: the energy spectrum ω(k)²|q̂(k)|² = 4A² sin²(Wk a/2) is flat across
//!   the whole Brillouin zone, so half its energy is zone-edge content that stays behind.

use std::f64::consts::PI;

use super::Lattice;
use crate::error::{LtiError, Result};

/// The envelope of a packet over its block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Envelope {
    /// sin²(π(j + 1)/(W + 1)) for j = 0…W−1.
    Hann,
    /// 1 on the block.
    Rectangular,
}

/// A displacement packet on the middle `width` particles, released from rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Packet {
    /// Carrier wave number k₀a (rad): π at the zone edge, 0 at the zone centre.
    pub ka: f64,
    /// Number of particles perturbed (the middle block).
    pub width: usize,
    /// Envelope over the block.
    pub envelope: Envelope,
    /// Peak displacement A (m).
    pub amplitude: f64,
}

impl Packet {
    /// The zone-edge packet of the seed's fig. 2.17(a): k₀a = π, Hann envelope, A = 1.
    pub fn zone_edge(width: usize) -> Packet {
        Packet {
            ka: PI,
            width,
            envelope: Envelope::Hann,
            amplitude: 1.0,
        }
    }

    /// The zone-centre packet of fig. 2.17(b): k₀a = 0, Hann envelope, A = 1.
    pub fn zone_centre(width: usize) -> Packet {
        Packet {
            ka: 0.0,
            ..Packet::zone_edge(width)
        }
    }

    /// The same packet with another envelope.
    pub fn with_envelope(self, envelope: Envelope) -> Packet {
        Packet { envelope, ..self }
    }

    /// The initial displacements q(0) of every particle of `lattice`.
    ///
    /// ```
    /// use ltikit::lti::lattice::{Boundary, Lattice, Packet};
    /// let lat = Lattice::new(128, Boundary::Periodic, 1.0).unwrap();
    /// let q = Packet::zone_edge(16).displacements(&lat).unwrap();
    /// assert_eq!(q.iter().filter(|x| **x != 0.0).count(), 16);
    /// assert!(q[56] > 0.0 && q[57] < 0.0 && q[55] == 0.0 && q[72] == 0.0);
    /// ```
    #[allow(clippy::float_cmp)] // k₀a exactly π selects the exact ±1 carrier
    pub fn displacements(&self, lattice: &Lattice) -> Result<Vec<f64>> {
        if !(self.ka.is_finite() && self.amplitude.is_finite()) {
            return Err(LtiError::invalid(format!(
                "a phonon packet needs a finite wave number and amplitude, got k₀a = {} and A = {}",
                self.ka, self.amplitude
            )));
        }
        let block = lattice.middle(self.width)?;
        let w = self.width as f64;
        let mut q = vec![0.0; lattice.n()];
        for (j, n) in block.enumerate() {
            let env = match self.envelope {
                Envelope::Hann => (PI * (j + 1) as f64 / (w + 1.0)).sin().powi(2),
                Envelope::Rectangular => 1.0,
            };
            // cos(πj) exactly ±1 at the zone edge.
            let carrier = if self.ka == PI {
                if j % 2 == 0 { 1.0 } else { -1.0 }
            } else {
                (self.ka * j as f64).cos()
            };
            q[n] = self.amplitude * env * carrier;
        }
        Ok(q)
    }
}
