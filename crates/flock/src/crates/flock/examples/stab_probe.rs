fn main() {
    for name in ["tr2003_fig9_sink_n100", "acc2004_fig4_sink_n100", "tr2003_fig7_obstacles_n100", "tanner2003_fig3_fixed_n10", "tac2006_fig11_alg2_n100"] {
        let base = flock::Scenario::load(format!("fixtures/{name}.ron")).unwrap();
        let stable = flock::largest_stable_step(&base).unwrap();
        print!("{name}: step {} stable {stable:.4e}", base.step);
        for factor in [0.5, 1.0, 2.0, 4.0, 8.0] {
            let mut s = base.clone();
            s.step = factor * stable;
            s.duration = (20.0f64).min(base.duration);
            let r = flock::run(&s, &mut ());
            print!("  x{factor}: {}", match r { Ok(_) => "ok".to_string(), Err(flock::RunError::Numerical(e)) => format!("blowup@{}", e.steps), Err(e) => format!("{e}") });
        }
        println!();
    }
}
