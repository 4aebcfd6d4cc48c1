//! The closed loop of a delayed loop by the method of steps (`Factored::delayed_feedback_response`,
//! `DelayedClosedForm`, `Factored::delayed_step_info`) against references derived
//! independently: the delay-differential equation solved interval by interval in exact
//! arithmetic (sympy), evaluated with 45 digits (mpmath).
//!
//! The reference script (sympy 1.x, mpmath; "method of steps on the DDE state form"):
//!
//! ```text
//! # first-order loop: y' = -a y + K (1 - y(t - T)), y = 0 on [0, T]; local time u = t - kT
//! y_k(u) = e^(-a u) y_(k-1)(T) + ∫_0^u e^(-a (u - s)) K (1 - y_(k-1)(s)) ds
//! # PI around e^(-sT)/(tau s + 1): y' = (-y + v(t - T))/tau, z' = 1 - y,
//! # v = Kp (1 - y + z/Ti); y = 0, z = t on [0, T]
//! y_k(u) = e^(-u/tau) y_(k-1)(T) + ∫_0^u e^(-(u - s)/tau) v_(k-1)(s)/tau ds
//! z_k(u) = z_(k-1)(T) + ∫_0^u (1 - y_k(s)) ds
//! ```
//!
//! (sympy `integrate` + `expand` on each interval with rational K, a, T, Kp, Ti, tau; values by
//! `evalf(45)`.) This never forms L^k nor partial fractions: it integrates the DDE itself.

#![allow(clippy::excessive_precision)] // the references are quoted as the script printed them

mod common;

use common::{c, real_root};
use ltikit::Root;
use ltikit::analysis::{DelayedClosedForm, Factored, Input, StepInfoOptions};

/// L = K/(s + a).
fn first_order(k: f64, a: f64) -> Factored {
    Factored::from_zpk(&[], &[real_root(-a)], k).unwrap()
}

/// L = C·G without the delay: C = Kp(1 + 1/(Ti s)), G = 1/(tau s + 1):
/// L = (Kp/tau)·(s + 1/Ti)/(s (s + 1/tau)).
fn pi_fopdt(kp: f64, ti: f64, tau: f64) -> Factored {
    Factored::from_zpk(
        &[real_root(-1.0 / ti)],
        &[real_root(0.0), real_root(-1.0 / tau)],
        kp / tau,
    )
    .unwrap()
}

/// The next smaller double.
fn before(t: f64) -> f64 {
    f64::from_bits(t.to_bits() - 1)
}

#[test]
fn first_order_loop_three_intervals_in_closed_form() {
    // K = 2, a = 1, T = 1/2. The script's closed forms (local time u = t − kT ∈ [0, 1/2]):
    //   [T, 2T]:  y = 2 − 2e^(−u)
    //   [2T, 3T]: y = 4u e^(−u) − 2 − 2e^(−1/2) e^(−u) + 4e^(−u)
    //   [3T, 4T]: y = −4u² e^(−u) − 8u e^(−u) + 4u e^(−1/2) e^(−u) + 6 − 8e^(−u)
    //                 − 2e^(−1) e^(−u) + 6e^(−1/2) e^(−u)
    // (by hand for the first: y' = −y + 2, y(T) = 0.)
    let e = |x: f64| x.exp();
    let exact = |t: f64| -> f64 {
        match t {
            t if t < 0.5 => 0.0,
            t if t < 1.0 => 2.0 - 2.0 * e(-(t - 0.5)),
            t if t < 1.5 => {
                let u = t - 1.0;
                4.0 * u * e(-u) - 2.0 - 2.0 * e(-0.5) * e(-u) + 4.0 * e(-u)
            }
            t => {
                let u = t - 1.5;
                -4.0 * u * u * e(-u) - 8.0 * u * e(-u) + 4.0 * u * e(-0.5) * e(-u) + 6.0
                    - 8.0 * e(-u)
                    - 2.0 * e(-1.0) * e(-u)
                    + 6.0 * e(-0.5) * e(-u)
            }
        }
    };
    // and the script's 45-digit values of the same
    let refs = [
        (0.3, 0.0),
        (0.75, 0.4423984338571902635096595),
        (1.0, 0.7869386805747331527924009),
        (1.2, 0.9367370071914938922060903),
        (1.5, 0.9034250759329158984317497),
        (1.8, 0.718900901040686013172509),
        (1.99, 0.6161321418036535103092126),
    ];
    let l = first_order(2.0, 1.0);
    let t: Vec<f64> = (0..2000).map(|i| i as f64 * 0.001).collect();
    let r = l.delayed_feedback_response(0.5, &Input::Step, &t).unwrap();
    assert_eq!(r.closed_form.len(), 3);
    let mut worst = 0.0f64;
    for (&ti, &yi) in t.iter().zip(&r.y) {
        worst = worst.max((yi - exact(ti)).abs());
    }
    for (ti, want) in refs {
        let got = r.closed_form.eval(ti);
        worst = worst.max((got - want).abs());
    }
    eprintln!("first-order loop, 3 intervals: max |y − exact| = {worst:.2e}");
    assert!(worst < 1e-13, "{worst}");
    // exactly 0 before T, and the error signal e = 1 − y
    assert!(t.iter().zip(&r.y).all(|(&ti, &yi)| ti >= 0.5 || yi == 0.0));
    assert!(
        r.t.iter()
            .zip(&r.error)
            .zip(&r.y)
            .all(|((_, e), y)| (e - (1.0 - y)).abs() < 1e-15)
    );
    assert!(
        r.max_cancellation_bound < 1e-13,
        "{}",
        r.max_cancellation_bound
    );
    assert!(r.closed_form_error < 1e-13, "{}", r.closed_form_error);
}

#[test]
fn pi_loop_around_fopdt_over_ten_delays() {
    // Kp = 1/2, Ti = 3/2, tau = 1, T = 1: the script's values (45 digits, rounded to 20) at
    // t = 0.05, 0.15, …, 10.95. Its first intervals: y = u/3 + 1/6 − e^(−u)/6 on [1, 2] (by
    // hand: y' = −y + 1/2 + u/3, y(0) = 0), y = −u²/18 + 2u/9 + u e^(−u)/36 + 7/12
    // − e^(−u)/12 − e^(−1) e^(−u)/6 on [2, 3].
    let refs: [(f64, f64); 110] = [
        (0.05, 0.0),
        (0.15, 0.0),
        (0.25, 0.0),
        (0.35, 0.0),
        (0.45, 0.0),
        (0.55, 0.0),
        (0.65, 0.0),
        (0.75, 0.0),
        (0.85, 0.0),
        (0.95, 0.0),
        (1.05, 0.024795095916547665151),
        (1.15, 0.073215337262490365462),
        (1.25, 0.12019986948809918863),
        (1.35, 0.16588531838021442761),
        (1.45, 0.21039530806303778448),
        (1.55, 0.25384169826991888411),
        (1.65, 0.29632570387316399202),
        (1.75, 0.33793890787649754881),
        (1.85, 0.37876417800854555501),
        (1.95, 0.41887649609091646551),
        (2.05, 0.45803463064044337625),
        (2.15, 0.49450449030317405389),
        (2.25, 0.5281741407053471114),
        (2.35, 0.55922597217694612093),
        (2.45, 0.58782295791115811621),
        (2.55, 0.61411069782242636806),
        (2.65, 0.6382192492468635445),
        (2.75, 0.66026476654527905969),
        (2.85, 0.68035096940079088784),
        (2.95, 0.69857045756664419708),
        (3.05, 0.71500846003587516546),
        (3.15, 0.72979880657965542797),
        (3.25, 0.74311816459894023598),
        (3.35, 0.75512848226067739972),
        (3.45, 0.76597640067558266436),
        (3.55, 0.77579506710344888126),
        (3.65, 0.7847057387223824754),
        (3.75, 0.79281920068407207866),
        (3.85, 0.80023701953213889946),
        (3.95, 0.80705265070670648551),
        (4.05, 0.81335240070214459408),
        (4.15, 0.81921510353096837489),
        (4.25, 0.82470952541732907267),
        (4.35, 0.82989446660898797645),
        (4.45, 0.83481995629455611352),
        (4.55, 0.83952830561547386606),
        (4.65, 0.84405502217521701977),
        (4.75, 0.84842960351802949648),
        (4.85, 0.85267622491245144365),
        (4.95, 0.85681433489305635723),
        (5.05, 0.86085917043750852522),
        (5.15, 0.86482222053624534569),
        (5.25, 0.86871175369239119077),
        (5.35, 0.87253339462382540249),
        (5.45, 0.87629063419365512452),
        (5.55, 0.8799852649983242781),
        (5.65, 0.88361775331712540404),
        (5.75, 0.88718755673555348093),
        (5.85, 0.89069339547420521531),
        (5.95, 0.89413348434279553088),
        (6.05, 0.89750573127352269592),
        (6.15, 0.90080790731704303942),
        (6.25, 0.90403778920526041185),
        (6.35, 0.90719327166146600978),
        (6.45, 0.9102724514023405129),
        (6.55, 0.91327368750136342145),
        (6.65, 0.91619564225416155436),
        (6.75, 0.91903730601784826786),
        (6.85, 0.92179800892702626411),
        (6.95, 0.92447742190521164349),
        (7.05, 0.92707554897989103588),
        (7.15, 0.92959271256431664433),
        (7.25, 0.93202953314321443122),
        (7.35, 0.93438690482120592165),
        (7.45, 0.93666596818734063352),
        (7.55, 0.93886808171820658589),
        (7.65, 0.94099479268843548977),
        (7.75, 0.94304780834672423027),
        (7.85, 0.94502896794318356199),
        (7.95, 0.94694021605366874168),
        (8.05, 0.94878357753345437893),
        (8.15, 0.95056113434167818033),
        (8.25, 0.95227500440446260927),
        (8.35, 0.95392732261828337474),
        (8.45, 0.95552022402829237205),
        (8.55, 0.95705582915748674782),
        (8.65, 0.95853623141770915071),
        (8.75, 0.95996348650079167694),
        (8.85, 0.96133960362525276815),
        (8.95, 0.96266653849876829662),
        (9.05, 0.96394618784747774635),
        (9.15, 0.96518038535867348411),
        (9.25, 0.96637089888244884645),
        (9.35, 0.96751942873974020698),
        (9.45, 0.96862760698873541218),
        (9.55, 0.96969699750864751703),
        (9.65, 0.9707290967687482099),
        (9.75, 0.97172533516065134821),
        (9.85, 0.97268707878260236781),
        (9.95, 0.97361563157555967866),
        (10.05, 0.97451223772184778424),
        (10.15, 0.97537808422789923261),
        (10.25, 0.97621430362292927979),
        (10.35, 0.97702197671519643165),
        (10.45, 0.97780213535670775382),
        (10.55, 0.9785557651757483947),
        (10.65, 0.97928380824438867105),
        (10.75, 0.97998716565511998239),
        (10.85, 0.98066669998699096435),
        (10.95, 0.98132323764707600757),
    ];
    let l = pi_fopdt(0.5, 1.5, 1.0);
    let t: Vec<f64> = refs.iter().map(|r| r.0).collect();
    let r = l.delayed_feedback_response(1.0, &Input::Step, &t).unwrap();
    assert_eq!(r.closed_form.len(), 10);
    let worst = refs
        .iter()
        .zip(&r.y)
        .map(|(&(_, want), got)| (got - want).abs())
        .fold(0.0, f64::max);
    let cf_worst = refs
        .iter()
        .map(|&(t, want)| (r.closed_form.eval(t) - want).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "PI/FOPDT, 10 delays: max |y − reference| = {worst:.2e} (values; rounding bound \
         {:.2e}), closed form {cf_worst:.2e}",
        r.max_cancellation_bound
    );
    assert!(worst < 1e-13, "{worst}");
    assert!(cf_worst < 1e-13, "{cf_worst}");
    assert!(
        worst <= r.max_cancellation_bound,
        "{worst} > {}",
        r.max_cancellation_bound
    );
    // the first interval by hand
    let y = &r.closed_form;
    for u in [0.1f64, 0.5, 0.9] {
        let want = u / 3.0 + 1.0 / 6.0 - (-u).exp() / 6.0;
        assert!((y.eval(1.0 + u) - want).abs() < 1e-15);
    }
}

#[test]
fn continuity_and_kinks_at_multiples_of_the_delay() {
    // PI/FOPDT: L strictly proper of relative degree 1, so y is continuous at kT; y′ jumps at
    // T from 0 to the high-frequency gain of L times the step, Kp/tau = 1/2, and at kT ≥ 2T by
    // h_k′(0⁺) = 0 (h_k ~ τ^k): C¹ there. The script's kink values (both sides agree to 20
    // digits): y(2) = 0.43868675980475961307, y(5) = 0.85884761154515728606.
    let l = pi_fopdt(0.5, 1.5, 1.0);
    let y = DelayedClosedForm::new(&l, 1.0, &Input::Step, 10.5).unwrap();
    assert!((y.eval(2.0) - 0.43868675980475961307).abs() < 1e-14);
    assert!((y.eval(5.0) - 0.85884761154515728606).abs() < 1e-14);
    for k in 1..=10 {
        let t = y.kink(k);
        let jump = (y.eval(t) - y.eval(before(t))).abs();
        assert!(jump < 1e-14, "k = {k}: jump {jump}");
    }
    assert_eq!(y.eval_derivative(before(1.0)), 0.0);
    assert!((y.eval_derivative(1.0) - 0.5).abs() < 1e-15);
    for k in 2..=10 {
        let t = y.kink(k);
        let d = (y.eval_derivative(t) - y.eval_derivative(before(t))).abs();
        assert!(d < 1e-12, "k = {k}: y′ jumps by {d}");
    }
    // A bi-proper loop jumps: L = (s + 2)/(s + 1) → D = 1: y(T⁺) − y(T⁻) = 1, at 2T −1.
    let bi = Factored::from_zpk(&[real_root(-2.0)], &[real_root(-1.0)], 1.0).unwrap();
    let yb = DelayedClosedForm::new(&bi, 1.0, &Input::Step, 2.5).unwrap();
    assert!((yb.eval(1.0) - yb.eval(before(1.0)) - 1.0).abs() < 1e-15);
    assert!((yb.eval(2.0) - yb.eval(before(2.0)) + 1.0).abs() < 1e-14);
}

#[test]
fn final_value_is_approached_by_a_stable_loop() {
    // PI/FOPDT (integrator: y∞ = 1) over 60 delays and the first-order loop over 40 delays
    // (y∞ = L(0)/(1 + L(0)) = 2/3). Stability: the Nyquist plot of L e^(−sT) does not
    // encircle −1 (first order: |L(jω)| = 1 at ω = √3 with phase −60° − 0.866 rad = −109.6°).
    let l = pi_fopdt(0.5, 1.5, 1.0);
    let r = l
        .delayed_feedback_response(1.0, &Input::Step, &[60.0])
        .unwrap();
    eprintln!(
        "PI/FOPDT at t = 60: |y − 1| = {:.2e}, cancellation bound {:.2e}, closed form off by {:.2e}",
        (r.y[0] - 1.0).abs(),
        r.max_cancellation_bound,
        r.closed_form_error
    );
    assert!((r.y[0] - 1.0).abs() < 1e-6, "{}", r.y[0]);
    let f = first_order(2.0, 1.0);
    let r = f
        .delayed_feedback_response(0.5, &Input::Step, &[20.0])
        .unwrap();
    eprintln!(
        "first-order K/a = 2 at t = 20 (40 pieces): |y − 2/3| = {:.2e}, cancellation bound {:.2e}, closed form off by {:.2e}",
        (r.y[0] - 2.0 / 3.0).abs(),
        r.max_cancellation_bound,
        r.closed_form_error
    );
    assert!(
        (r.y[0] - 2.0 / 3.0).abs() < 1e-5 + r.max_cancellation_bound,
        "{}",
        r.y[0]
    );
}

#[test]
fn impulse_and_other_inputs() {
    // Impulse into L = K/(s + a): L^k ↔ K^k τ^(k−1) e^(−aτ)/(k − 1)!, so
    // y(t) = Σ_k (−1)^(k+1) K^k (t − kT)^(k−1) e^(−a(t − kT))/(k − 1)!.
    let (k, a, t_d) = (1.5, 2.0, 0.3);
    let l = first_order(k, a);
    let t: Vec<f64> = (0..300).map(|i| i as f64 * 0.01).collect();
    let r = l
        .delayed_feedback_response(t_d, &Input::Impulse, &t)
        .unwrap();
    for (&ti, &yi) in t.iter().zip(&r.y) {
        let mut want = 0.0;
        let mut fact = 1.0;
        for j in 1..=9 {
            let tau = ti - j as f64 * t_d;
            if tau < 0.0 {
                break;
            }
            if j > 1 {
                fact *= (j - 1) as f64;
            }
            let sign = if j % 2 == 1 { 1.0 } else { -1.0 };
            want += sign * k.powi(j) * tau.powi(j - 1) * (-a * tau).exp() / fact;
        }
        assert!((yi - want).abs() < 1e-14, "t = {ti}: {yi} vs {want}");
    }
    // The ramp response's derivative is the step response, and the step's the impulse's.
    let l = pi_fopdt(0.5, 1.5, 1.0);
    let ramp = DelayedClosedForm::new(&l, 1.0, &Input::Ramp, 6.0).unwrap();
    let step = DelayedClosedForm::new(&l, 1.0, &Input::Step, 6.0).unwrap();
    let imp = DelayedClosedForm::new(&l, 1.0, &Input::Impulse, 6.0).unwrap();
    for x in [0.5, 1.3, 2.7, 4.4, 5.9] {
        assert!(
            (ramp.eval_derivative(x) - step.eval(x)).abs() < 1e-13,
            "{x}"
        );
        assert!((step.eval_derivative(x) - imp.eval(x)).abs() < 1e-13, "{x}");
    }
    // sin and cos: cos' = −ω sin + δ… ; check d/dt of the cos response against ω·(sin → y)
    // through the transforms: Y_cos·s = ω·… is not simpler; instead sin(ωt) = Im e^(jωt):
    // the sin response's derivative equals ω times the cos response (U_sin·s = ω·U_cos).
    let w = 1.7;
    let ys = DelayedClosedForm::new(&l, 1.0, &Input::Sin(w), 6.0).unwrap();
    let yc = DelayedClosedForm::new(&l, 1.0, &Input::Cos(w), 6.0).unwrap();
    for x in [1.3, 2.7, 4.4, 5.9] {
        assert!(
            (ys.eval_derivative(x) - w * yc.eval(x)).abs() < 1e-13,
            "{x}"
        );
    }
}

#[test]
fn step_metrics_of_the_first_order_loop() {
    // K = 2, a = 1, T = 1/2, y∞ = 2/3. From the closed forms above:
    // - 10 % and 90 % of 2/3 on [T, 2T] where y = 2 − 2e^(−u): u = ln(30/29), ln(10/7);
    // - the peak on [2T, 3T]: y′ = e^(−u)(2e^(−1/2) − 4u) = 0 at u* = e^(−1/2)/2, where
    //   y = 4e^(−u*) − 2 (using 4u* = 2e^(−1/2)).
    let l = first_order(2.0, 1.0);
    let horizon = 12.0;
    let s = l
        .delayed_step_info(0.5, horizon, true, &StepInfoOptions::default())
        .unwrap()
        .unwrap();
    assert!((s.steady_state - 2.0 / 3.0).abs() < 1e-16);
    assert!((s.rise_start.unwrap() - (0.5 + (30.0f64 / 29.0).ln())).abs() < 1e-14);
    assert!((s.rise_end.unwrap() - (0.5 + (10.0f64 / 7.0).ln())).abs() < 1e-14);
    let u_star = (-0.5f64).exp() / 2.0;
    assert!((s.peak_time.unwrap() - (1.0 + u_star)).abs() < 1e-9);
    let peak = 4.0 * (-u_star).exp() - 2.0;
    assert!((s.peak.unwrap() - peak).abs() < 1e-14);
    assert!((s.overshoot_percent.unwrap() - (peak / (2.0 / 3.0) - 1.0) * 100.0).abs() < 1e-11);
    assert!(s.note("peak").unwrap().contains("over the horizon"));
    // Against a dense evaluation (10⁶ points): the extremes bracket the sampled ones, and
    // the settling time is the last sample outside the band to within the spacing.
    dense_check(&l, 0.5, horizon, &s);
    // Not stable (declared by the caller): no metrics.
    assert!(
        l.delayed_step_info(0.5, horizon, false, &StepInfoOptions::default())
            .unwrap()
            .is_none()
    );
}

#[test]
fn step_metrics_of_the_pi_loop() {
    let l = pi_fopdt(0.5, 1.5, 1.0);
    let horizon = 25.0;
    let s = l
        .delayed_step_info(1.0, horizon, true, &StepInfoOptions::default())
        .unwrap()
        .unwrap();
    assert_eq!(s.steady_state, 1.0);
    // rise start on [1, 2] by hand: u/3 + 1/6 − e^(−u)/6 = 0.1 — checked densely below
    dense_check(&l, 1.0, horizon, &s);
    // a horizon too short to settle: the settling time is refused with a note
    let short = l
        .delayed_step_info(1.0, 8.0, true, &StepInfoOptions::default())
        .unwrap()
        .unwrap();
    assert!(short.settling_time.is_none());
    assert!(
        short
            .note("settling_time")
            .unwrap()
            .contains("still outside")
    );
}

/// Compares the metrics with a dense sampling of the same closed form (10⁶ + 1 points).
fn dense_check(l: &Factored, delay: f64, horizon: f64, s: &ltikit::analysis::StepInfo) {
    let n = 1_000_000;
    let h = horizon / n as f64;
    let y = DelayedClosedForm::new(l, delay, &Input::Step, horizon).unwrap();
    let yinf = s.steady_state;
    let (mut peak, mut peak_t, mut last_out) = (0.0f64, 0.0, 0.0);
    let (mut first10, mut first90) = (None, None);
    for i in 0..=n {
        let t = i as f64 * h;
        let v = y.eval(t);
        if v.abs() > peak {
            peak = v.abs();
            peak_t = t;
        }
        if first10.is_none() && v >= 0.1 * yinf {
            first10 = Some(t);
        }
        if first90.is_none() && v >= 0.9 * yinf {
            first90 = Some(t);
        }
        if (v - yinf).abs() > 0.02 * yinf.abs() {
            last_out = t;
        }
    }
    eprintln!(
        "dense check: peak {peak:.15} at {peak_t:.6} vs {:.15} at {:.6}; settling {last_out:.6} vs {:?}",
        s.peak.unwrap(),
        s.peak_time.unwrap(),
        s.settling_time
    );
    // the exact peak is at least every sample and within O(h²) curvature of the best one
    assert!(s.peak.unwrap() >= peak - 1e-14);
    assert!(s.peak.unwrap() - peak < 1e-6);
    assert!((s.peak_time.unwrap() - peak_t).abs() <= 2.0 * h);
    assert!((s.rise_start.unwrap() - first10.unwrap()).abs() <= h);
    assert!((s.rise_end.unwrap() - first90.unwrap()).abs() <= h);
    let st = s.settling_time.unwrap();
    assert!(
        st >= last_out - 1e-12 && st <= last_out + h,
        "{st} vs {last_out}"
    );
}

#[test]
fn bad_input_is_refused_clearly() {
    let l = first_order(2.0, 1.0);
    let msg = |d: f64, t: &[f64]| {
        l.delayed_feedback_response(d, &Input::Step, t)
            .unwrap_err()
            .to_string()
    };
    assert!(msg(0.0, &[1.0]).contains("delay"));
    assert!(msg(-0.5, &[1.0]).contains("delay"));
    assert!(msg(f64::NAN, &[1.0]).contains("delay"));
    assert!(msg(f64::INFINITY, &[1.0]).contains("delay"));
    assert!(msg(0.5, &[f64::INFINITY]).contains("finite"));
    assert!(msg(0.5, &[-1.0]).contains("≥ 0"));
    let e = msg(0.001, &[100.0]);
    assert!(
        e.contains("100001") && e.contains("MAX_MARCH_INTERVALS"),
        "{e}"
    );
    // a discrete-time loop
    let d = first_order(1.0, 0.5).with_domain(ltikit::lti::Domain::discrete(0.1).unwrap());
    assert!(
        d.delayed_feedback_response(1.0, &Input::Step, &[1.0])
            .is_err()
    );
    // an improper loop
    let imp = Factored::from_zpk(&[Root::new(c(-1.0, 0.0), 2)], &[real_root(-2.0)], 1.0).unwrap();
    assert!(
        imp.delayed_feedback_response(1.0, &Input::Step, &[1.0])
            .is_err()
    );
}
