//! Factor once: how many times each command factors its plant (counted on the calling thread
//! with `factorizations_on_this_thread`, not timed).

use ltikit::analysis::factorizations_on_this_thread;

/// Factorisations performed by one in-process command line.
fn count(args: &[&str]) -> usize {
    let before = factorizations_on_this_thread();
    let mut argv = vec!["ltikit"];
    argv.extend_from_slice(args);
    ltikit::cli::run_from(argv).unwrap();
    factorizations_on_this_thread() - before
}

fn out(name: &str) -> String {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("factor_counts");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).display().to_string()
}

#[test]
fn every_command_factors_each_plant_once() {
    let png = out("bode.png");
    let cases: Vec<(Vec<&str>, usize)> = vec![
        (vec!["analyze", "--num", "2", "--den", "1 3 2 0"], 1),
        (vec!["margins", "--num", "2", "--den", "1 3 2 0"], 1),
        (vec!["residue", "--num", "1 3", "--den", "1 3 3 1"], 1),
        (vec!["freq", "--den", "1 0.2 1"], 1),
        (vec!["response", "--den", "1 2 1", "--input", "step"], 1),
        (
            vec![
                "bode",
                "--num",
                "2",
                "--den",
                "1 3 2 0",
                "--asymptotes",
                "-o",
                &png,
            ],
            1,
        ),
        (vec!["step", "--den", "1 0.2 1", "-o", &png], 1),
        (
            vec!["step", "--den", "1 0.2 1", "--den", "1 2 1", "-o", &png],
            2,
        ),
        (vec!["pzmap", "--den", "1 2 1", "-o", &png], 1),
        (
            vec!["nyquist", "--num", "2", "--den", "1 3 2 0", "-o", &png],
            1,
        ),
    ];
    // A loop: the controller and the plant are factored once each; L, T, S are formed from
    // known roots (counted, no root finding): margins builds L, S and T, step L and T.
    let pid = "pid:kp=2,ki=1,kd=0.5,tf=0.01";
    let loops: Vec<(Vec<&str>, usize)> = vec![
        (vec!["margins", "--den", "1 0.4 4", "--controller", pid], 5),
        (vec!["analyze", "--den", "1 0.4 4", "--controller", pid], 4),
        (
            vec!["step", "--den", "1 0.4 4", "--controller", pid, "-o", &png],
            4,
        ),
    ];
    for (args, want) in cases.into_iter().chain(loops) {
        assert_eq!(count(&args), want, "{args:?}");
    }
}

#[test]
fn the_demo_factors_each_plant_a_handful_of_times() {
    let dir = out("demo");
    let n = count(&["demo", "--out", &dir]);
    // Each plant of the tour is factored once: 6 textbook plants, 4 damping cases; each
    // linearised equilibrium with an input twice (its transfer function, and the display form
    // with the rounding noise of the linearisation removed): pendulum, MEMS, rigid body, heavy
    // top, gyroscope channels, double pendulum (1 740 before the factored core, with fewer
    // models). The closed-loop section adds 9: the PID loop factors C and G once and forms L,
    // T and (for Ms, Mt) S and T from the known characteristic roots; the cancellation example
    // factors C and G and forms L; the lattice's channels are factored from their state
    // space. Measured 39 (45 while the demo also checked the seed's analytic second-order
    // responses, six more plants; tests/response.rs checks those). The digital-control section
    // (issue 20) adds 35: every sampled plant is a new factored form (the spring–mass–damper
    // at five periods, the tank's three ZOH transfer functions), and each of the six PID
    // loops (continuous, five periods) forms its sampled plant, its C(z) and its L, T and S
    // once. Measured 74. The dead-time section (issue 21) adds 38: the tank and C, the loop
    // L and L·e^(−sT); the powers L^k, k ≤ 10, of the method of steps (each a factored form
    // built from L's roots, no root finding), once for the samples and once for the step
    // metrics; and the three Padé loops (approximant, plant·approximant, L, T). Measured 112.
    // The diagram section (issue 24) adds 1, the connected cascade; the design section (issue
    // 23) 2, the full and the reduced lattice channel for their Bode diagrams (the LQR, the
    // norms and the truncation work on state space, not on factored forms). Measured 115.
    eprintln!("demo: {n} factorisations");
    assert!(n <= 117, "{n}");
}
