//! The factored form of a SISO plant: computed once, read by every analysis.
//!
//! A plant enters ltikit as ODE coefficients (a [`TransferFunction`](crate::TransferFunction)) or as zeros, poles and a
//! gain; a state-space channel will enter through its eigenvalues, transmission zeros and
//! first Markov parameter. Whatever the source, it is factored **once** into a [`Factored`]:
//!
//! - poles and zeros with exact multiplicities, the common roots that cancel, and the reduced
//!   (lowest-terms) poles and zeros ([`PoleZero`]);
//! - the gain k of G(s) = k·Π(s − zᵢ)/Π(s − pᵢ) (as given and reduced alike);
//! - the source itself, kept for what it does better than the roots: the coefficients of a
//!   transfer function evaluate G accurately where the roots are ill-conditioned (clusters),
//!   give the dc gain exactly and realise the response in controllable canonical form;
//! - lazily, the evaluation form of the frequency kernels (built at the first frequency
//!   response, margin or grid, then shared; it belongs to this core, `bode/`).
//!
//! Stability, modes, partial fractions, closed forms and exact responses, step metrics,
//! frequency response, margins, Nyquist, asymptotes and the automatic grids are methods of
//! [`Factored`]; the [`TransferFunction`](crate::TransferFunction) methods of the same names are one-line delegates that
//! factor first. A caller that runs several analyses of one plant factors it once:
//!
//! ```
//! use ltikit::TransferFunction;
//! let g = TransferFunction::from_descending(&[2.0], &[1.0, 3.0, 2.0, 0.0]).unwrap();
//! let f = g.factored().unwrap();          // the only root finding
//! let a = f.analyze().unwrap();           // poles, stability, modes, step metrics
//! let m = f.margins().unwrap();           // margins on the same factors
//! assert!(a.stability.internal_reason.contains("marginally"));
//! assert!((m.gain_margin.unwrap() - 3.0).abs() < 1e-12);
//! ```
//!
//! Nothing downstream needs polynomial coefficients that a factored source cannot provide:
//! where the coefficients help (accuracy, the canonical realisation, the polynomials of the
//! margin equations) the analyses ask the source, and a source without coefficients answers
//! from the factors.
//!
//! # The files
//! Every source builds its parts and hands them to one constructor, `form::assemble`, which
//! counts the factorisation ([`factorizations_on_this_thread`]) and starts the evaluation form
//! empty:
//!
//! | file | what |
//! |---|---|
//! | `form.rs` | [`Factored`], `assemble`, what the factored form answers directly |
//! | `coefficients.rs` | from ODE coefficients ([`Factored::from_tf`], [`TransferFunction::factored`](crate::TransferFunction::factored)) |
//! | `exact.rs` | from coefficients as typed: the certified structure ([`Factored::from_exact`]) |
//! | `zpk.rs` | from zeros, poles and gain ([`Factored::from_zpk`]) |
//! | `plant.rs`, `ss_source.rs`, `ss_modal.rs` | from a plant, a state-space model or channel ([`Factored::from_state_space`]), a second-order one in modal coordinates |
//! | `interconnect.rs` | series, parallel, feedback |
//! | `minreal.rs` | near pole-zero pairs, and their cancellation within a tolerance ([`Factored::minreal`]) |
//! | `pole_zero.rs`, `low_frequency.rs`, `decision.rs`, `source.rs` | the parts: roots, the asymptote K·s^k, how the structure was decided, the source |
//! | `series.rs` | products and power series of factors in scaled form |
//! | `discretize.rs` | sampling ([`Factored::c2d`]: ZOH poles e^(pT) with their multiplicities) and its inverse ([`Factored::d2c`]) |
//! | `bode/` | the cached evaluation form of the frequency kernels |
//! | `display.rs` | G(s) as text |

mod bode;
mod coefficients;
mod decision;
mod discretize;
mod display;
mod exact;
mod form;
mod interconnect;
mod low_frequency;
mod minreal;
mod plant;
mod pole_zero;
pub(crate) mod series;
mod source;
mod ss_modal;
mod ss_source;
mod zpk;

pub(crate) use bode::{BodeForm, mul_pow2};
pub use decision::StructurePath;
pub use form::{Factored, factorizations_on_this_thread};
pub use interconnect::Feedback;
pub(crate) use interconnect::{close, series_parts};
pub use minreal::{NEAR_PAIR_REL, NearPair};
pub use pole_zero::{MAX_FACTORED_ORDER, PoleZero};
pub(crate) use series::ScaledProduct;
pub(crate) use ss_source::SsSource;
