//! Lyapunov, Sylvester and Riccati equations against scipy 1.17.1 (LAPACK) values, and the
//! `ltikit lyap | sylvester | care | dare` commands.
//!
//! The scipy references were computed once in a throwaway virtual environment:
//! `scipy.linalg.solve_continuous_are(A, B, Q, R, s=S)`, `solve_discrete_are(...)`,
//! `solve_continuous_lyapunov(A, -Q)`, `solve_discrete_lyapunov(A, Q)` on the matrices
//! below, printed with 17 digits. scipy's Riccati solvers are accurate to ~1e-13 here, so the
//! comparison is at 1e-11 relative; our own residuals are checked tighter.

mod common;

use ltikit::numeric::linalg::{care, dare, dlyap, lyap};
use nalgebra::DMatrix;

fn m(rows: usize, cols: usize, v: &[f64]) -> DMatrix<f64> {
    DMatrix::from_row_slice(rows, cols, v)
}

fn close(got: &DMatrix<f64>, want: &DMatrix<f64>, tol: f64) {
    let err = (got - want).norm() / want.norm();
    assert!(
        err <= tol,
        "relative error {err:e}\n got {got}\nwant {want}"
    );
}

#[test]
fn care_with_cross_term_matches_scipy() {
    let a = m(3, 3, &[0.0, 1.0, 0.0, 0.0, 0.0, 1.0, -1.0, -2.0, -3.0]);
    let b = m(3, 1, &[0.0, 0.0, 1.0]);
    let q = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![1.0, 2.0, 3.0]));
    let r = m(1, 1, &[0.5]);
    let s = m(3, 1, &[0.1, 0.0, 0.2]);
    let sol = care(&a, &b, &q, &r, Some(&s)).unwrap();
    let scipy = m(
        3,
        3,
        &[
            2.62077236136036,
            2.2936180698044817,
            0.3219544457292888,
            2.2936180698044817,
            5.928008643297999,
            1.0721047439269284,
            0.3219544457292888,
            1.0721047439269284,
            0.6285413339528527,
        ],
    );
    close(&sol.x, &scipy, 1e-11);
    assert!(sol.residual < 1e-15, "{}", sol.residual);
}

#[test]
fn dare_matches_scipy() {
    // Two inputs, unstable A.
    let a = m(2, 2, &[1.1, 0.2, 0.0, 0.9]);
    let b = m(2, 2, &[1.0, 0.0, 0.5, 1.0]);
    let q = m(2, 2, &[2.0, 0.5, 0.5, 1.0]);
    let r = m(2, 2, &[1.0, 0.2, 0.2, 2.0]);
    let sol = dare(&a, &b, &q, &r, None).unwrap();
    let scipy = m(
        2,
        2,
        &[
            2.9202183351090243,
            0.4975825956583647,
            0.4975825956583647,
            1.6151860352824943,
        ],
    );
    close(&sol.x, &scipy, 1e-11);
    // Singular A (a delay chain) with a cross term.
    let a = m(2, 2, &[0.0, 1.0, 0.0, 0.0]);
    let b = m(2, 1, &[0.0, 1.0]);
    let s = m(2, 1, &[0.2, 0.1]);
    let sol = dare(&a, &b, &DMatrix::identity(2, 2), &m(1, 1, &[1.0]), Some(&s)).unwrap();
    let scipy = m(
        2,
        2,
        &[
            0.986593601239682,
            -0.00628209783689481,
            -0.00628209783689481,
            1.9836498760873968,
        ],
    );
    close(&sol.x, &scipy, 1e-11);
    assert!(sol.residual < 1e-15, "{}", sol.residual);
}

#[test]
fn lyapunov_matches_scipy() {
    let a = m(3, 3, &[-1.0, 2.0, 0.0, 0.0, -3.0, 1.0, 0.5, 0.0, -2.0]);
    let q = m(3, 3, &[2.0, 1.0, 0.0, 1.0, 3.0, 0.5, 0.0, 0.5, 1.0]);
    // The continuous solution is rational (x₁₁ = 144/61); scipy's digits.
    let scipy = m(
        3,
        3,
        &[
            2.360655737704919,
            0.6803278688524591,
            0.5573770491803284,
            0.680327868852459,
            0.5819672131147542,
            0.24590163934426248,
            0.5573770491803282,
            0.24590163934426257,
            0.3893442622950822,
        ],
    );
    let sol = lyap(&a, &q).unwrap();
    close(&sol.x, &scipy, 1e-14);
    assert!((sol.x[(0, 0)] - 144.0 / 61.0).abs() < 1e-14);
    let scipy = m(
        3,
        3,
        &[
            9.429634762847815,
            -6.577833857238786,
            -2.0515435166676648,
            -6.577833857238785,
            11.702631793293195,
            1.849797422744008,
            -2.0515435166676648,
            1.849797422744009,
            2.4710072111941486,
        ],
    );
    let sol = dlyap(&(&a * 0.3), &q).unwrap();
    close(&sol.x, &scipy, 1e-13);
}

#[cfg(feature = "cli")]
mod cli {
    use super::common::{json, ltikit, stdout};

    #[test]
    fn care_text_and_json() {
        let args = [
            "care", "--a", "0 1; 0 0", "--b", "0; 1", "--q", "1 0; 0 1", "--r", "1",
        ];
        let out = stdout(&args);
        assert!(out.contains("K = [       1  1.73205 ]"), "{out}");
        assert!(out.contains("-0.866025 ± 0.5j"), "{out}");
        let mut with_json = args.to_vec();
        with_json.push("--json");
        let v = json(&with_json);
        let k = v["gain"][0].as_array().unwrap();
        assert!((k[1].as_f64().unwrap() - 3f64.sqrt()).abs() < 1e-14);
        assert!(v["residual"].as_f64().unwrap() < 1e-15);
        assert!(v["condition"].as_f64().unwrap() > 0.0);
    }

    #[test]
    fn lyap_from_a_file_and_refusals() {
        let dir = std::env::temp_dir().join(format!("ltikit-equations-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("eq.toml");
        std::fs::write(&f, "a = [[-1, 0], [0, -2]]\nq = \"1 1; 1 1\"\n").unwrap();
        let v = json(&["lyap", "--from", f.to_str().unwrap(), "--json"]);
        // x_ij = q_ij/(−λᵢ − λⱼ).
        assert!((v["x"][0][1].as_f64().unwrap() - 1.0 / 3.0).abs() < 1e-15);
        let v = json(&["lyap", "--a", "-1 0; 0 -2", "--b", "1; 0", "--json"]);
        assert!((v["l"][0][0].as_f64().unwrap() - 0.5f64.sqrt()).abs() < 4e-16);
        for (args, needle) in [
            (
                &["lyap", "--a", "0 1; -1 0", "--q", "1 0; 0 1"][..],
                "no unique solution",
            ),
            (
                &["care", "--a", "1", "--b", "1", "--q", "1", "--r", "-1"][..],
                "positive definite",
            ),
            (
                &[
                    "care", "--a", "1 0; 0 2", "--b", "1; 0", "--q", "1 0; 0 1", "--r", "1",
                ][..],
                "not stabilisable",
            ),
            (
                &["dare", "--a", "1 2", "--b", "1", "--q", "1", "--r", "1"][..],
                "square",
            ),
            (
                &["sylvester", "--a", "nan", "--b", "1", "--c", "1"][..],
                "NaN",
            ),
        ] {
            let o = ltikit(args);
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
            assert!(
                err.contains(needle) && err.lines().count() == 1,
                "{args:?}: {err}"
            );
        }
    }
}

#[test]
fn orders_beyond_the_limits_are_refused_before_any_work() {
    // MAX_EQUATION_STATES = 512 for Lyapunov/Sylvester, MAX_DESIGN_STATES = 256 for the
    // Riccati equations (a 2n × 2n Hamiltonian): the error names the order and the limit
    use ltikit::limits::{MAX_DESIGN_STATES, MAX_EQUATION_STATES};
    use ltikit::numeric::linalg::{care, dare, lyap, sylvester};
    let big = DMatrix::<f64>::identity(MAX_EQUATION_STATES + 1, MAX_EQUATION_STATES + 1) * -1.0;
    let e = lyap(&big, &big).unwrap_err().to_string();
    assert!(e.contains("513") && e.contains("512"), "{e}");
    assert!(sylvester(&big, &big, &big).is_err());
    let n = MAX_DESIGN_STATES + 1;
    let a = DMatrix::<f64>::identity(n, n) * -1.0;
    let b = DMatrix::<f64>::identity(n, 1);
    let one = DMatrix::<f64>::identity(1, 1);
    let q = DMatrix::<f64>::identity(n, n);
    let e = care(&a, &b, &q, &one, None).unwrap_err().to_string();
    assert!(e.contains("257") && e.contains("256"), "{e}");
    assert!(dare(&(a * -0.5), &b, &q, &one, None).is_err());
}
