//! Gramians, Hankel singular values, the H2 norm and balanced truncation (issue 23 item 3):
//! closed forms, the a priori bound against the certified measured error, and k = n.

mod common;

#[path = "../benches/common/norms.rs"]
mod norms_input;

use ltikit::StateSpace;
use ltikit::analysis::norms::{
    GramianKind, ReducedOrder, balanced_truncation, gramian, h2_norm, hankel_singular_values,
    hinf_norm,
};
use ltikit::lti::Domain;
use ltikit::lti::lattice::{Boundary, Lattice, Output};
use nalgebra::DMatrix;

fn one(x: f64) -> DMatrix<f64> {
    DMatrix::from_element(1, 1, x)
}

/// ẍ + 2ζω ẋ + ω² x = u, y = x.
fn second_order(z: f64, w: f64) -> StateSpace {
    StateSpace::new(
        DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, -2.0 * z * w]),
        DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
        DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
        one(0.0),
    )
    .unwrap()
}

/// Closed forms: ‖1/(s + a)‖₂ = 1/√(2a); ‖1/(s² + 2ζωs + ω²)‖₂² = 1/(4ζω³) (∫|g|² of the
/// impulse response, Parseval); a feedthrough makes the continuous norm infinite.
#[test]
fn h2_closed_forms() {
    for a in [0.5, 1.0, 7.0] {
        let n = h2_norm(&StateSpace::new(one(-a), one(1.0), one(1.0), one(0.0)).unwrap()).unwrap();
        assert!(
            common::rel(n.value, 1.0 / (2.0 * a).sqrt()) < 1e-15,
            "a = {a}: {n:?}"
        );
    }
    for (z, w) in [(0.1, 2.0), (0.7, 0.5), (1e-3, 1.0), (3.0, 10.0)] {
        let n = h2_norm(&second_order(z, w)).unwrap();
        let exact = (1.0 / (4.0 * z * w * w * w)).sqrt();
        assert!(
            common::rel(n.value, exact) < 1e-13,
            "ζ = {z}, ω = {w}: {} vs {exact}",
            n.value
        );
        assert!(n.residual < 1e-14);
    }
    let d = StateSpace::new(one(-1.0), one(1.0), one(1.0), one(1.0)).unwrap();
    assert!(
        h2_norm(&d)
            .unwrap()
            .infinite
            .unwrap()
            .contains("feedthrough")
    );
    let unstable = StateSpace::new(one(1.0), one(1.0), one(1.0), one(0.0)).unwrap();
    assert!(
        h2_norm(&unstable)
            .unwrap()
            .infinite
            .unwrap()
            .contains("s = 1")
    );
}

/// Discrete time: z/(z − a) = 1 + a/(z − a) has the impulse response 1, a, a², … so
/// ‖G‖₂² = 1/(1 − a²) (the feedthrough counts); 1/(z − a) the same.
#[test]
fn h2_discrete() {
    let dt = Domain::discrete(0.1).unwrap();
    for a in [0.5f64, -0.9, 0.99] {
        let exact = (1.0 / (1.0 - a * a)).sqrt();
        let g = StateSpace::new(one(a), one(1.0), one(a), one(1.0))
            .unwrap()
            .with_domain(dt);
        assert!(
            common::rel(h2_norm(&g).unwrap().value, exact) < 1e-14,
            "a = {a}"
        );
        let g = StateSpace::new(one(a), one(1.0), one(1.0), one(0.0))
            .unwrap()
            .with_domain(dt);
        assert!(
            common::rel(h2_norm(&g).unwrap().value, exact) < 1e-14,
            "a = {a}"
        );
    }
}

/// b·c/(s + a): P = b²/(2a), Q = c²/(2a), σ = |b·c|/(2a); for 1/(s + 1), σ = 1/2.
#[test]
fn hankel_singular_values_of_first_order_systems() {
    for (a, b, c) in [(1.0, 1.0, 1.0), (3.0, 2.0, -5.0), (0.01, 1e-3, 1.0)] {
        let ss = StateSpace::new(one(-a), one(b), one(c), one(0.0)).unwrap();
        let h = hankel_singular_values(&ss).unwrap();
        assert!(
            common::rel(h.values[0], (b * c).abs() / (2.0 * a)) < 1e-15,
            "{a} {b} {c}"
        );
        let p = gramian(&ss, GramianKind::Controllability).unwrap().matrix();
        assert!(common::rel(p[(0, 0)], b * b / (2.0 * a)) < 1e-15);
        let q = gramian(&ss, GramianKind::Observability).unwrap().matrix();
        assert!(common::rel(q[(0, 0)], c * c / (2.0 * a)) < 1e-15);
    }
    // Σσᵢ² = trace(PQ), and the HSVs are invariant under a change of state coordinates
    let ss = norms_input::random_stable(30, 2, 2, 1);
    let h = hankel_singular_values(&ss).unwrap();
    let pq = h.controllability.matrix() * h.observability.matrix();
    let sum: f64 = h.values.iter().map(|s| s * s).sum();
    assert!(
        common::rel(sum, pq.trace()) < 1e-10,
        "{sum} vs {}",
        pq.trace()
    );
    let t = DMatrix::from_fn(30, 30, |i, j| {
        if i == j {
            2.0
        } else if j == i + 1 {
            0.5
        } else {
            0.0
        }
    });
    let ti = t.clone().try_inverse().unwrap();
    let moved = StateSpace::new(&t * &ss.a * &ti, &t * &ss.b, &ss.c * &ti, ss.d.clone()).unwrap();
    let h2 = hankel_singular_values(&moved).unwrap();
    for (x, y) in h.values.iter().zip(&h2.values).take(20) {
        assert!(common::rel(*x, *y) < 1e-9, "{x} vs {y}");
    }
}

/// The a priori bound 2·Σ_{i>k} σᵢ is never below the certified ‖G − G_r‖∞ (its upper end
/// checked against the bound with its lower end: the measured error is an interval).
fn bound_holds(ss: &StateSpace, orders: &[usize], what: &str) {
    for &k in orders {
        let r = balanced_truncation(ss, ReducedOrder::Order(k)).unwrap();
        assert_eq!(r.reduced.order(), k);
        assert!(
            r.error.lower <= r.bound * (1.0 + 1e-9),
            "{what}, k = {k}: measured {} > bound {}",
            r.error.lower,
            r.bound
        );
        // and the error is at least the first neglected σ (the lower bound σ_{k+1})
        if k < r.hsv.len() {
            assert!(r.error.upper >= r.hsv[k] * (1.0 - 1e-9), "{what}, k = {k}");
        }
    }
}

#[test]
fn bound_against_measured_error_random_and_lattice() {
    bound_holds(
        &norms_input::random_stable(30, 2, 2, 1),
        &[1, 2, 5, 10, 20],
        "random 30",
    );
    bound_holds(
        &norms_input::random_stable(12, 1, 3, 7),
        &[1, 3, 6],
        "random 12",
    );
    // a damped lattice channel (N = 16, fixed ends, force on 1, particle 8 measured)
    let lat = Lattice::new(16, Boundary::Fixed, 1.0)
        .and_then(|l| l.with_damping(0.05, 0.0))
        .and_then(|l| l.with_input(1))
        .and_then(|l| l.with_output(Output::Particle(8)))
        .and_then(|l| l.state_space())
        .unwrap();
    bound_holds(&lat, &[2, 8, 16, 24], "lattice");
    // discrete: the zoh-sampled random model
    let d = norms_input::random_stable(12, 1, 3, 7)
        .c2d(0.1, ltikit::lti::Discretization::Zoh)
        .unwrap();
    bound_holds(&d, &[2, 6], "discrete");
}

/// k = n reproduces the transfer function (the measured error is rounding), and the error
/// mode picks the smallest order whose bound meets it.
#[test]
fn full_order_and_error_mode() {
    let ss = norms_input::random_stable(12, 1, 3, 7);
    let full = hinf_norm(&ss).unwrap().lower;
    let r = balanced_truncation(&ss, ReducedOrder::Order(12)).unwrap();
    assert!(r.error.upper < 1e-10 * full, "{:?} vs {full}", r.error);
    assert_eq!(r.bound, 0.0);
    let e = 1e-2 * full;
    let r = balanced_truncation(&ss, ReducedOrder::Error(e)).unwrap();
    let k = r.reduced.order();
    assert!(r.bound <= e && r.error.upper <= e);
    let tail = |k: usize| 2.0 * r.hsv[k..].iter().sum::<f64>();
    assert!(k == 0 || tail(k - 1) > e, "k = {k} is not the smallest");
}

/// Unstable A: one error naming the eigenvalue; an order beyond the states is refused.
#[test]
fn bad_input() {
    let unstable = StateSpace::new(one(2.0), one(1.0), one(1.0), one(0.0)).unwrap();
    let e = balanced_truncation(&unstable, ReducedOrder::Order(1))
        .unwrap_err()
        .to_string();
    assert!(e.contains("s = 2") && e.contains("stable"), "{e}");
    let ss = StateSpace::new(one(-2.0), one(1.0), one(1.0), one(0.0)).unwrap();
    let e = balanced_truncation(&ss, ReducedOrder::Order(3))
        .unwrap_err()
        .to_string();
    assert!(e.contains("exceeds"), "{e}");
    assert!(balanced_truncation(&ss, ReducedOrder::Error(f64::NAN)).is_err());
}

/// A model that is not stable by more than rounding has no Gramian: the error names the
/// eigenvalue (found on the Lyapunov kernel's own Schur form), continuous and discrete.
#[test]
fn gramians_of_unstable_models_name_the_eigenvalue() {
    // a rigid-body mode (eigenvalue exactly 0) beside a stable one
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, -1.0]);
    let b = DMatrix::from_column_slice(2, 1, &[0.0, 1.0]);
    let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
    let ss = StateSpace::new(a, b, c, DMatrix::zeros(1, 1)).unwrap();
    for kind in [GramianKind::Controllability, GramianKind::Observability] {
        let e = gramian(&ss, kind).unwrap_err().to_string();
        assert!(
            e.contains("a Gramian of this model")
                && e.contains("s = 0")
                && e.contains("imaginary axis"),
            "{e}"
        );
    }
    assert!(hankel_singular_values(&ss).is_err());
    // discrete: z = 1.5 outside the unit circle
    let d = StateSpace::new(one(1.5), one(1.0), one(1.0), one(0.0))
        .unwrap()
        .with_domain(Domain::Discrete { dt: 0.1 });
    let e = gramian(&d, GramianKind::Controllability)
        .unwrap_err()
        .to_string();
    assert!(e.contains("z = 1.5") && e.contains("unit circle"), "{e}");
}
