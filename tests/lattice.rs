//! The seed's linear lattice (§2.4) against closed forms: eigenvalues and dispersion
//! (eq. 2.71), the modal matrix of §2.4.1.2, energy conservation and the modal energies
//! (2.78), single-mode motion, the damped modal solution against e^{At}x₀, the force →
//! displacement channel, phonon packets, bad input, the heat map.
//!
//! Closed forms used (derived in `ltikit::lti::lattice::closed_form`): periodic
//! ωₚ = 2ω0 sin(πp/N), p = 0…N−1, mode shapes e^{2πjpn/N}; fixed ends
//! ωₖ = 2ω0 sin(πk/(2(N + 1))), shapes sin(πkn/(N + 1)).

use ltikit::LtiError;
use ltikit::lti::lattice::{
    Boundary, Envelope, LATTICE_PARAMS, Lattice, Output, Packet, modal_free_response,
};
use ltikit::numeric::{eigenvalues, expm};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;
use std::f64::consts::PI;

fn lattice(n: usize, b: Boundary, w0: f64) -> Lattice {
    Lattice::new(n, b, w0).unwrap()
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// A deterministic pseudo-random vector in [−1, 1) (64-bit LCG, Knuth's MMIX constants).
fn pseudo_random(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

// ---------------------------------------------------------------- eigenvalues, dispersion

#[test]
fn frequencies_match_the_closed_forms_at_n_128() {
    // Issue target: every eigenvalue within 1e-12·ω0 of ±j·2ω0 sin(πk/N).
    for b in [Boundary::Periodic, Boundary::Fixed] {
        for w0 in [1.0, 3.7, 1e-3] {
            let lat = lattice(128, b, w0);
            let modes = lat.modes().unwrap();
            let err = max_abs_diff(&modes.omega, &lat.frequencies_closed_form()) / w0;
            assert!(err < 1e-12, "{b:?} ω0 = {w0}: {err:e}");
            let ev = modes.eigenvalues();
            let exact = lat.eigenvalues_closed_form();
            let e = ev
                .iter()
                .zip(&exact)
                .map(|(a, b)| (a - b).norm())
                .fold(0.0, f64::max);
            assert!(e < 1e-12 * w0, "{b:?} eigenvalues of A: {e:e}");
        }
    }
}

#[test]
fn small_lattices_by_hand() {
    // Periodic N = 4: K = circulant(2, −1, 0, −1) has eigenvalues 0, 2, 2, 4.
    let w = lattice(4, Boundary::Periodic, 1.0).modes().unwrap().omega;
    let r2 = 2f64.sqrt();
    assert!(max_abs_diff(&w, &[0.0, r2, r2, 2.0]) < 1e-15);
    // Periodic N = 2: both neighbours are the same particle, K = [[2, −2], [−2, 2]]: 0, 4.
    let w = lattice(2, Boundary::Periodic, 1.0).modes().unwrap().omega;
    assert!(max_abs_diff(&w, &[0.0, 2.0]) < 1e-15);
    // Fixed N = 2: K = [[2, −1], [−1, 2]] has eigenvalues 1 and 3.
    let w = lattice(2, Boundary::Fixed, 1.0).modes().unwrap().omega;
    assert!(max_abs_diff(&w, &[1.0, 3f64.sqrt()]) < 1e-15);
    // Odd periodic N = 7: no zone-edge mode; three degenerate pairs.
    let lat = lattice(7, Boundary::Periodic, 2.0);
    let w = lat.modes().unwrap().omega;
    assert!(max_abs_diff(&w, &lat.frequencies_closed_form()) < 1e-14);
    assert!((w[5] - w[6]).abs() < 1e-14 && (w[6] - 4.0 * (3.0 * PI / 7.0).sin()).abs() < 1e-14);
}

#[test]
fn eigenvalues_of_a_from_the_general_solver() {
    // The 2N-state A through the crate's general (Hessenberg QR) eigenvalues, independent
    // of the symmetric route: fixed ends have N distinct pairs ±jωₖ.
    let lat = lattice(16, Boundary::Fixed, 1.0);
    let mut ev = eigenvalues(&lat.state_space().unwrap().a).unwrap();
    let mut exact = lat.eigenvalues_closed_form();
    let key = |z: &Complex64| (z.im * 1e9).round() as i64;
    ev.sort_by_key(key);
    exact.sort_by_key(key);
    let e = ev
        .iter()
        .zip(&exact)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(e < 1e-12, "{e:e}");
    // Periodic: the rigid mode is a 2×2 Jordan block at 0, which any backward-stable
    // solver scatters by ~√eps; the other eigenvalues come out at the rounding level.
    let lat = lattice(16, Boundary::Periodic, 1.0);
    let ev = eigenvalues(&lat.state_space().unwrap().a).unwrap();
    let exact = lat.frequencies_closed_form();
    for z in &ev {
        let nearest = exact
            .iter()
            .map(|w| (z - Complex64::new(0.0, w * z.im.signum())).norm())
            .fold(f64::INFINITY, f64::min);
        let tol = if z.norm() < 1e-4 { 1e-6 } else { 1e-12 };
        assert!(nearest < tol, "{z}: {nearest:e}");
    }
}

#[test]
fn mode_shapes_obey_the_dispersion_law() {
    // The wave number read off each computed mode shape, and ω(k) = 2ω0 sin(ka/2) (2.71).
    for (n, w0) in [(64, 2.5), (128, 1.0)] {
        for b in [Boundary::Periodic, Boundary::Fixed] {
            let lat = lattice(n, b, w0);
            let m = lat.modes().unwrap();
            assert_eq!(m.wavenumber, lat.wavenumbers_closed_form());
            for (w, k) in m.omega.iter().zip(&m.wavenumber) {
                let law = ltikit::lti::lattice::closed_form::dispersion(w0, *k);
                assert!((w - law).abs() < 1e-12 * w0, "{b:?} N = {n} k = {k}");
            }
        }
    }
}

// ---------------------------------------------------------------- the modal matrix T

#[test]
fn computed_t_diagonalises_omega_in_increasing_order() {
    for b in [Boundary::Periodic, Boundary::Fixed] {
        let lat = lattice(128, b, 1.0);
        let c = lat.modes().unwrap().diagonal_check(&lat).unwrap();
        assert!(c.off_diagonal < 1e-13, "{b:?} {c:?}");
        assert!(c.diagonal < 1e-13, "{b:?} {c:?}");
        assert!(c.orthogonality < 1e-13, "{b:?} {c:?}");
        assert!(c.order_violation < 1e-13, "{b:?} {c:?}");
    }
}

#[test]
fn the_seeds_closed_form_t_is_orthogonal_and_diagonalises_omega() {
    for (n, b) in [
        (128, Boundary::Periodic),
        (7, Boundary::Periodic),
        (2, Boundary::Periodic),
        (33, Boundary::Fixed),
    ] {
        let lat = lattice(n, b, 1.0);
        let t = lat.modal_matrix_closed_form();
        let gram = t.transpose() * &t - DMatrix::identity(n, n);
        assert!(gram.amax() < 1e-13, "{n} {b:?}");
        let d = t.transpose() * lat.omega_matrix() * &t;
        let w = lat.frequencies_closed_form();
        let target = DMatrix::from_diagonal(&DVector::from_iterator(n, w.iter().map(|x| -x * x)));
        assert!((d - target).amax() < 1e-13, "{n} {b:?}");
    }
}

#[test]
fn computed_eigenspaces_are_the_closed_form_ones() {
    // Degenerate pairs make single eigenvectors arbitrary; the projector on each distinct
    // frequency's eigenspace is not.
    for b in [Boundary::Periodic, Boundary::Fixed] {
        let lat = lattice(48, b, 1.0);
        let t = lat.modes().unwrap().t;
        let tc = lat.modal_matrix_closed_form();
        let w = lat.frequencies_closed_form();
        let mut k = 0;
        while k < 48 {
            let mut e = k + 1;
            while e < 48 && (w[e] - w[k]).abs() < 1e-9 {
                e += 1;
            }
            let p = t.columns(k, e - k) * t.columns(k, e - k).transpose();
            let pc = tc.columns(k, e - k) * tc.columns(k, e - k).transpose();
            assert!((p - pc).amax() < 1e-12, "{b:?} modes {k}…{e}");
            k = e;
        }
    }
}

// ---------------------------------------------------------------- exact motion, energy

#[test]
fn energy_is_conserved_and_every_modal_energy_is_invariant() {
    for b in [Boundary::Periodic, Boundary::Fixed] {
        let lat = lattice(128, b, 1.3);
        let modes = lat.modes().unwrap();
        let q0 = pseudo_random(128, 1);
        let v0 = pseudo_random(128, 2);
        let t: Vec<f64> = (0..=500).map(|i| i as f64 * 0.4).collect();
        let tr = lat.simulate(&modes, &q0, &v0, &t).unwrap();
        let e = lat.total_energy(&tr);
        let drift = e.iter().map(|x| (x - e[0]).abs()).fold(0.0, f64::max) / e[0];
        assert!(drift < 1e-13, "{b:?} total energy drift {drift:e}");
        let d = tr.modal_energy_drift(&modes);
        assert!(d < 1e-13, "{b:?} modal energy drift {d:e}");
        // Σ over particles of the site energies = total = Σ over modes of Hₖ (2.78).
        let all = lat.block_energy(&tr, 0..128);
        let h = tr.modal_energies(&modes);
        for i in [0, 250, 500] {
            assert!((all[i] - e[i]).abs() < 1e-13 * e[0]);
            assert!((h.column(i).sum() - e[i]).abs() < 1e-13 * e[0]);
        }
    }
}

#[test]
fn a_single_mode_stays_in_its_mode() {
    // q(0) = a column of the seed's T (independent of the eigensolver): q(t) = q(0) cos ωt.
    let lat = lattice(128, Boundary::Periodic, 1.0);
    let modes = lat.modes().unwrap();
    let tc = lat.modal_matrix_closed_form();
    let w = lat.frequencies_closed_form();
    for col in [1usize, 10, 77, 127] {
        let q0: Vec<f64> = tc.column(col).iter().copied().collect();
        let t = [0.0, 3.3, 40.0, 250.0];
        let tr = lat.simulate(&modes, &q0, &[0.0; 128], &t).unwrap();
        for (i, ti) in t.iter().enumerate() {
            let c = (w[col] * ti).cos();
            let e = (0..128)
                .map(|n| (tr.q[(n, i)] - q0[n] * c).abs())
                .fold(0.0, f64::max);
            assert!(e < 1e-12, "mode {col}, t = {ti}: {e:e}");
        }
        // Its energy ½ω² stays in modes of its own frequency, up to the computed
        // eigenvectors' error, ~ (eps‖K‖/gap)² of it: for the zone edge the gap in ω² to the
        // nearest pair is 4 sin²(π/64) ≈ 0.0096, so ≈ 3e-26 (measured 2.4e-25).
        let h = tr.modal_energies(&modes);
        for k in 0..128 {
            if (modes.omega[k] - w[col]).abs() > 1e-9 {
                assert!(h.column(3)[k] < 1e-23, "mode {col} leaked into {k}");
            }
        }
    }
    // The rigid mode: a uniform velocity translates the ring, q = v t.
    let tr = lat
        .simulate(&modes, &[0.0; 128], &[0.5; 128], &[8.0])
        .unwrap();
    assert!(tr.q.iter().all(|q| (q - 4.0).abs() < 1e-13));
}

/// x(t) = e^{At}x₀ of the 2N-state model, by the crate's matrix exponential.
fn expm_motion(lat: &Lattice, q0: &[f64], v0: &[f64], t: f64) -> DVector<f64> {
    let ss = lat.state_space().unwrap();
    let n = lat.n();
    let x0 = DVector::from_iterator(2 * n, q0.iter().chain(v0).copied());
    expm(&(&ss.a * t)).unwrap() * x0
}

#[test]
fn damped_modal_solution_matches_the_matrix_exponential() {
    // Under-, over- and mixed damping (η large: the high modes are overdamped, cₖ > 2ωₖ),
    // the undamped rigid mode of the periodic ring with η only, and no damping.
    for b in [Boundary::Periodic, Boundary::Fixed] {
        for (gamma, eta) in [(0.3, 0.2), (5.0, 0.0), (0.0, 3.0), (0.0, 0.0)] {
            let lat = lattice(6, b, 1.4).with_damping(gamma, eta).unwrap();
            let modes = lat.modes().unwrap();
            let q0 = pseudo_random(6, 3);
            let v0 = pseudo_random(6, 4);
            let times = [0.7, 4.0, 15.0];
            let tr = lat.simulate(&modes, &q0, &v0, &times).unwrap();
            for (i, &t) in times.iter().enumerate() {
                let x = expm_motion(&lat, &q0, &v0, t);
                let e = (0..6)
                    .map(|k| {
                        (x[k] - tr.q[(k, i)])
                            .abs()
                            .max((x[6 + k] - tr.v[(k, i)]).abs())
                    })
                    .fold(0.0, f64::max);
                assert!(e < 1e-12, "{b:?} γ {gamma} η {eta} t {t}: {e:e}");
            }
        }
    }
}

#[test]
fn packets_of_the_demo_move_as_the_matrix_exponential_says() {
    // N = 128: the zone-edge Hann packet of 16 particles on the undamped ring at t = 10 and
    // 50 s, and on the damped fixed lattice (γ = 0.005, η = 0.01) at t = 20 s.
    let ring = lattice(128, Boundary::Periodic, 1.0);
    let damped = lattice(128, Boundary::Fixed, 1.0)
        .with_damping(0.005, 0.01)
        .unwrap();
    for (lat, times) in [(ring, vec![10.0, 50.0]), (damped, vec![20.0])] {
        let modes = lat.modes().unwrap();
        let q0 = Packet::zone_edge(16).displacements(&lat).unwrap();
        let scale = q0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let tr = lat.simulate(&modes, &q0, &[0.0; 128], &times).unwrap();
        for (i, &t) in times.iter().enumerate() {
            let x = expm_motion(&lat, &q0, &[0.0; 128], t);
            let e = (0..128)
                .map(|k| (x[k] - tr.q[(k, i)]).abs())
                .fold(0.0, f64::max);
            assert!(e < 1e-10 * scale, "{:?} t = {t}: {e:e}", lat.boundary());
        }
    }
}

#[test]
fn critical_damping_is_the_limit_of_both_sides() {
    // c = 2ω exactly selects the (1, t) branch; it must agree with c = 2ω(1 ± 1e-9).
    for t in [0.5, 3.0, 20.0] {
        let (z, v) = modal_free_response(2.0, 1.0, 0.3, -1.1, t);
        for c in [2.0 * (1.0 + 1e-9), 2.0 * (1.0 - 1e-9)] {
            let (z2, v2) = modal_free_response(c, 1.0, 0.3, -1.1, t);
            assert!(
                (z - z2).abs() < 1e-8 && (v - v2).abs() < 1e-8,
                "t {t} c {c}"
            );
        }
        // Exact: z = e^{−t}(z0 + (v0 + z0) t).
        let exact = (-t).exp() * (0.3 + (-1.1 + 0.3) * t);
        assert!((z - exact).abs() < 1e-15);
    }
}

// ---------------------------------------------------------------- the channel

#[test]
fn channel_matches_the_modal_sum_and_the_static_compliance() {
    let lat = lattice(9, Boundary::Fixed, 2.0)
        .with_mass(3.0)
        .unwrap()
        .with_input(2)
        .unwrap()
        .with_output(Output::Particle(7))
        .unwrap();
    let ss = lat.state_space().unwrap();
    let sum = lat.modal_sum(7, 2).unwrap();
    // Static compliance of the fixed chain: (K⁻¹)ᵢⱼ = i(N + 1 − j)/(N + 1) for i ≤ j (the
    // discrete Green's function of the (−1, 2, −1) matrix), G(0) = (K⁻¹)ᵢⱼ/(m ω0²).
    let g0 = 2.0 * (10.0 - 7.0) / 10.0 / (3.0 * 4.0);
    assert!((sum.eval(Complex64::new(0.0, 0.0)).re - g0).abs() < 1e-15);
    let x = ss.a.clone().lu().solve(&ss.b).unwrap(); // G(0) = −C A⁻¹ B
    assert!((-(&ss.c * x)[(0, 0)] - g0).abs() < 1e-14);
    // C(jωI − A)⁻¹B on the state space against the modal sum.
    for w in [0.3, 1.0, 2.2, 3.9] {
        let s = Complex64::new(0.0, w);
        let n = ss.order();
        let m = DMatrix::from_fn(n, n, |i, j| {
            let d = if i == j { s } else { Complex64::new(0.0, 0.0) };
            d - Complex64::new(ss.a[(i, j)], 0.0)
        });
        let b = ss.b.map(|x| Complex64::new(x, 0.0));
        let g = (ss.c.map(|x| Complex64::new(x, 0.0)) * m.lu().solve(&b).unwrap())[(0, 0)];
        let e = sum.eval(s);
        assert!((g - e).norm() < 1e-12 * e.norm(), "ω = {w}");
    }
}

#[test]
fn modal_sum_weights_are_the_numerical_mode_products() {
    // wₖ = Σ over the modes of frequency ωₖ of Tᵢₖ Tⱼₖ / m (invariant under rotations within a
    // degenerate pair), with exact zeros where a mode has a node at i or j.
    for (b, n, i, j) in [
        (Boundary::Periodic, 128, 1, 1),
        (Boundary::Periodic, 128, 5, 37),
        (Boundary::Fixed, 127, 64, 64),
        (Boundary::Fixed, 30, 3, 11),
    ] {
        let lat = lattice(n, b, 1.0);
        let modes = lat.modes().unwrap();
        let sum = lat.modal_sum(i, j).unwrap();
        for (w, om) in sum.weight.iter().zip(&sum.omega) {
            let numeric: f64 = (0..n)
                .filter(|&k| (modes.omega[k] - om).abs() < 1e-9)
                .map(|k| modes.t[(i - 1, k)] * modes.t[(j - 1, k)])
                .sum();
            assert!((numeric - w).abs() < 1e-13, "{b:?} {i}→{j} ω = {om}");
        }
    }
    // Collocated on the ring: one mode per distinct frequency, 2(N/2 + 1) = 130 states.
    assert_eq!(
        lattice(128, Boundary::Periodic, 1.0)
            .modal_sum(1, 1)
            .unwrap()
            .minimal_order(),
        130
    );
    // Fixed, N = 127, driven and measured at the centre: antisymmetric modes (even k) vanish.
    assert_eq!(
        lattice(127, Boundary::Fixed, 1.0)
            .modal_sum(64, 64)
            .unwrap()
            .minimal_order(),
        128
    );
}

// ---------------------------------------------------------------- phonon packets

#[test]
fn packets_live_where_their_names_say() {
    let lat = lattice(128, Boundary::Periodic, 1.0);
    let modes = lat.modes().unwrap();
    let fraction_above_half_zone = |p: Packet| {
        let h = modes
            .energies(&p.displacements(&lat).unwrap(), &[0.0; 128])
            .unwrap();
        let total: f64 = h.iter().sum();
        let high: f64 = (0..128)
            .filter(|&k| modes.wavenumber[k] > 0.5 * PI)
            .map(|k| h[k])
            .sum();
        high / total
    };
    assert!(fraction_above_half_zone(Packet::zone_edge(16)) > 0.999);
    assert!(fraction_above_half_zone(Packet::zone_centre(16)) < 1e-3);
}

#[test]
fn flat_zone_centre_packet_spreads_its_energy_over_the_zone() {
    // A plateau of W ones: pair p (k = 2πp/N) holds (4/N) ω0² sin²(Wka/2) (Fourier analysis of
    // the plateau: ω²|q̂|² = 4 sin²(Wk/2), spread over the pair's two modes).
    let lat = lattice(128, Boundary::Periodic, 1.0);
    let modes = lat.modes().unwrap();
    let q = Packet::zone_centre(16)
        .with_envelope(Envelope::Rectangular)
        .displacements(&lat)
        .unwrap();
    let h = modes.energies(&q, &[0.0; 128]).unwrap();
    for p in 1..64 {
        let pair: f64 = (0..128)
            .filter(|&k| (modes.wavenumber[k] - 2.0 * PI * p as f64 / 128.0).abs() < 1e-12)
            .map(|k| h[k])
            .sum();
        let exact = 4.0 / 128.0 * (16.0 * PI * p as f64 / 128.0).sin().powi(2);
        // Near the zone edge the computed pairs are only ~1e-12 accurate in their
        // orientation (close frequencies): measured 1.7e-14.
        assert!((pair - exact).abs() < 1e-13, "p = {p}");
    }
    assert!((h.iter().sum::<f64>() - 1.0).abs() < 1e-14); // two end bonds stretched by 1
}

#[test]
fn zone_edge_energy_stays_and_zone_centre_energy_leaves() {
    let lat = lattice(128, Boundary::Periodic, 1.0);
    let modes = lat.modes().unwrap();
    let block = lat.middle(16).unwrap();
    let t = [0.0, 25.0];
    let share = |p: Packet| {
        let tr = lat
            .simulate(&modes, &p.displacements(&lat).unwrap(), &[0.0; 128], &t)
            .unwrap();
        let e = lat.block_energy(&tr, block.clone());
        e[1] / lat.total_energy(&tr)[0]
    };
    assert!(share(Packet::zone_edge(16)) > 0.9);
    assert!(share(Packet::zone_centre(16)) < 1e-3);
}

// ---------------------------------------------------------------- bad input

#[test]
fn bad_parameters_are_one_line_errors() {
    let p = |k: &str, v: f64| (k.to_string(), v);
    let cases: [(Vec<(String, f64)>, &str); 9] = [
        (vec![p("N", 1.0)], "parameter N = 1 is invalid"),
        (vec![p("N", 2000.0)], "integer 2…512"),
        (
            vec![p("w0", 0.0)],
            "parameter w0 = 0 is invalid: the natural frequency",
        ),
        (vec![p("w0", f64::NAN)], "NaN"),
        (vec![p("periodic", 3.0)], "1 (periodic) or 0 (fixed)"),
        (vec![p("N", 10.0), p("input", 11.0)], "parameter input = 11"),
        (
            vec![p("N", 10.0), p("output", 12.0)],
            "parameter output = 12",
        ),
        (vec![p("m", -2.0)], "parameter m = -2"),
        (
            vec![p("alpha", 2.0), p("beta", -1.0)],
            "αβ = -2 must be > 0",
        ),
    ];
    for (o, want) in cases {
        let msg = Lattice::from_params(&o).unwrap_err().to_string();
        assert!(msg.contains(want), "{msg}");
        assert!(!msg.contains('\n'));
    }
    assert!(matches!(
        Lattice::new(1, Boundary::Fixed, 1.0),
        Err(LtiError::InvalidParameter { .. })
    ));
    assert!("hinged".parse::<Boundary>().is_err());
    assert_eq!(LATTICE_PARAMS.len(), 10);
    let lat = lattice(4, Boundary::Fixed, 1.0);
    assert!(lat.clone().with_input(5).is_err());
    assert!(lat.clone().with_output(Output::Particle(0)).is_err());
    assert!(lat.modal_sum(0, 1).is_err());
}

#[test]
fn bad_simulation_input_is_refused() {
    let lat = lattice(4, Boundary::Periodic, 1.0);
    let modes = lat.modes().unwrap();
    let z = [0.0; 4];
    assert!(lat.simulate(&modes, &[0.0; 3], &z, &[1.0]).is_err());
    assert!(
        lat.simulate(&modes, &[f64::NAN, 0.0, 0.0, 0.0], &z, &[1.0])
            .is_err()
    );
    assert!(lat.simulate(&modes, &z, &z, &[-1.0]).is_err());
    assert!(lat.simulate(&modes, &z, &z, &[f64::INFINITY]).is_err());
    assert!(lat.simulate(&modes, &z, &z, &[]).is_err());
    assert!(lat.simulate(&modes, &z, &z, &vec![0.0; 2_000_000]).is_err());
    let other = lattice(5, Boundary::Periodic, 1.0).modes().unwrap();
    assert!(lat.simulate(&other, &z, &z, &[1.0]).is_err());
    assert!(Packet::zone_edge(5).displacements(&lat).is_err());
}

// ---------------------------------------------------------------- the heat map

#[cfg(feature = "plot")]
#[test]
fn space_time_heat_map_is_written() {
    use ltikit::plot::{HeatMap, PlotOptions, heatmap_png};
    let lat = lattice(32, Boundary::Fixed, 1.0);
    let modes = lat.modes().unwrap();
    let t: Vec<f64> = (0..50).map(|i| i as f64 * 0.5).collect();
    let tr = lat
        .simulate(
            &modes,
            &Packet::zone_edge(8).displacements(&lat).unwrap(),
            &[0.0; 32],
            &t,
        )
        .unwrap();
    let values: Vec<f64> = (0..t.len())
        .flat_map(|i| tr.q.column(i).iter().copied().collect::<Vec<_>>())
        .collect();
    let mut h = HeatMap::new(values, 32, t.len(), (0.5, 32.5), (-0.25, 24.75)).unwrap();
    h.z_label = "q_{n} (m)".into();
    let dir = std::env::temp_dir().join(format!("ltikit-lattice-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("heat.png");
    heatmap_png(
        &path,
        &h,
        &PlotOptions {
            size: (640, 480),
            ..Default::default()
        },
    )
    .unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    // IHDR: width and height, big-endian, at bytes 16…24.
    assert_eq!(
        u32::from_be_bytes([bytes[16], bytes[17], bytes[18], bytes[19]]),
        640
    );
    assert_eq!(
        u32::from_be_bytes([bytes[20], bytes[21], bytes[22], bytes[23]]),
        480
    );
    std::fs::remove_dir_all(&dir).unwrap();
    // Mismatched sizes are an error, not a panic.
    assert!(HeatMap::new(vec![0.0; 10], 3, 3, (0.0, 1.0), (0.0, 1.0)).is_err());
}
