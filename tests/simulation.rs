//! The simulation loop: `End:` runs once after the step the user asked
//! for, environments answer query modules between steps through the
//! `Environment` seam, and options reach grammar components.

mod common;

use common::lsys;

use lsys::internals::derive::{DeriveError, DeriveOptions, ModuleStore};
use lsys::internals::simulation::{Environment, Simulation, StepContext};

const END_FIXTURE: &str = "tests/fixtures/simulation/end_after_target.lsys";

#[test]
fn end_runs_after_the_step_count_given_on_the_command_line() {
    // The fixture's End: reads sq[n - 6]: in range only after step 6.
    let o = lsys(&["derive", END_FIXTURE, "-n", "6"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert_eq!(String::from_utf8_lossy(&o.stdout).trim(), "A(6)");
}

#[test]
fn end_runs_after_the_files_derivation_length_without_n() {
    let o = lsys(&["derive", END_FIXTURE]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(65), "{err}");
    assert!(err.contains("in the `End:` block at step 3"), "{err}");
}

#[test]
fn end_runs_once_when_the_target_is_zero() {
    // With no step at all End: still runs, once, after the axiom: n is 0,
    // so sq[-6] fails at step 0.
    let o = lsys(&["derive", END_FIXTURE, "-n", "0"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("in the `End:` block at step 0"), "{err}");
}

/// An environment that answers every `?P(x)` with the step number and
/// counts how often it was asked.
struct StepCounter<'a> {
    calls: &'a std::cell::Cell<u32>,
}

impl Environment for StepCounter<'_> {
    fn after_step(
        &mut self,
        ctx: &StepContext<'_>,
        string: &mut ModuleStore,
    ) -> Result<(), DeriveError> {
        self.calls.set(self.calls.get() + 1);
        let q = ctx.program.symbols.get("?P").expect("the grammar has ?P");
        let mut at = 0;
        let offsets: Vec<(usize, usize)> = string
            .iter()
            .map(|m| {
                let here = (at, m.params.len());
                at += m.params.len();
                (m.sym as usize, here.0)
            })
            .filter(|&(s, _)| s == q as usize)
            .collect();
        for (_, off) in offsets {
            string.params_mut()[off] = f64::from(ctx.step) * 10.0;
        }
        Ok(())
    }
}

#[test]
fn an_environment_answers_after_the_axiom_and_every_step_before_end_each() {
    // cpfg's query module ?P answered by a custom environment (after the
    // turtle's own answer, so the custom one wins); B copies the answer.
    let text = "Lsystem: 1\nderivation length: 2\nAxiom: A ?P(0,0,0)\n\
                ?P(x,y,z) --> ?P(x,y,z) B(x)\nendlsystem\n";
    let c = lsys::internals::pipeline::compile(
        &lsys::internals::load::Input::Text {
            name: "q.l".into(),
            text: text.into(),
        },
        &Default::default(),
    )
    .unwrap_or_else(|_| panic!("compiles"));
    let calls = std::cell::Cell::new(0);
    let mut sim = Simulation::new(&c.program, &c.compiled, DeriveOptions::default(), 2)
        .unwrap()
        .with_environment(Box::new(StepCounter { calls: &calls }));
    // The environment was added after the axiom's answer: it is asked from
    // step 1 on.
    sim.run(&mut |_, _| {}).unwrap();
    assert_eq!(calls.get(), 2);
    let s = sim.current().display(&c.program.symbols);
    // Step 1 read the turtle's answer for the axiom (0), step 2 this
    // environment's answer for step 1 (10), each new B written just after
    // ?P; the final ?P holds 20.
    assert_eq!(s, "A ?P(20,0,0) B(10) B(0)");
}

fn stats(args: &[&str]) -> Result<serde_json::Value, String> {
    let mut full = vec!["build"];
    full.extend_from_slice(args);
    full.push("--stats");
    let o = lsys(&full);
    if o.status.success() {
        Ok(serde_json::from_slice(&o.stdout).unwrap())
    } else {
        Err(String::from_utf8_lossy(&o.stderr).into_owned())
    }
}

#[test]
fn namespaced_defines_set_a_grammar_components_own_defines() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p.glb");
    let out = out.to_str().unwrap();
    let tris = |extra: &[&str]| {
        let mut a = vec!["std:pailou", "-o", out];
        a.extend_from_slice(extra);
        stats(&a).unwrap()["triangles"].as_u64().unwrap()
    };
    let default = tris(&[]);
    // Three Toukung levels instead of the middle Toukung's default five.
    let fewer = tris(&["-D", "TM.NTL=3"]);
    let more = tris(&["-D", "TM.NTL=8"]);
    assert!(
        fewer < default && default < more,
        "{fewer} {default} {more}"
    );
    // An unknown namespace is a diagnostic that lists the components.
    let err = stats(&["std:pailou", "-o", out, "-D", "TMM.NTL=3"]).unwrap_err();
    assert!(err.contains("lsys::options::unknown_namespace"), "{err}");
    assert!(err.contains("did you mean `TM`?"), "{err}");
}

/// A folder with `g.lsys` placing grammar component `Sub`, which grows a
/// stochastic bush of a few hundred segments.
fn stochastic_component() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let parts = dir.path().join("components");
    std::fs::create_dir(&parts).unwrap();
    std::fs::write(
        parts.join("Sub.lsys"),
        "derivation length: 5\nangle: 30\nAxiom: A\n\
         A --> F [+A] [-A] F A : 0.5\nA --> F [&A] F A : 0.5\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("g.lsys"), "Axiom: ~Sub(1)\n").unwrap();
    dir
}

#[test]
fn seed_and_limits_reach_grammar_components() {
    let dir = stochastic_component();
    let g = dir.path().join("g.lsys");
    let g = g.to_str().unwrap();
    let out = dir.path().join("m.glb");
    let out = out.to_str().unwrap();
    let tris = |seed: &str| stats(&[g, "-o", out, "--seed", seed]).unwrap()["triangles"].clone();
    // The outer grammar draws no random number: only a seed that reaches
    // the component can change the model (its productions differ in size;
    // the model is normalised to the unit box, so count triangles).
    assert_eq!(tris("1"), tris("1"));
    assert_ne!(tris("1"), tris("2"));
    // The outer string has one module; the component's has thousands.
    let err = stats(&[g, "-o", out, "--max-modules", "100"]).unwrap_err();
    assert!(err.contains("Sub"), "{err}");
    assert!(err.contains("100"), "{err}");
}

#[test]
fn dialect_option_decides_the_profile_for_every_stage() {
    let dir = tempfile::tempdir().unwrap();
    let g = dir.path().join("third.lsys");
    std::fs::write(&g, "axiom: A(1) % B\nA(x) --> A(x/3)\n").unwrap();
    let g = g.to_str().unwrap();
    let derive = |extra: &[&str]| {
        let mut a = vec!["derive", g, "-n", "2"];
        a.extend_from_slice(extra);
        let o = lsys(&a);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).trim().to_string()
    };
    // The paper's profile: f64 parameters, `%` a roll that stays.
    assert_eq!(derive(&[]), "A(0.1111111111111111) % B");
    // cpfg's: f32 parameters printed short, `%` cuts the rest of the branch.
    assert_eq!(derive(&["--dialect", "cpfg"]), "A(0.11111111)");
}
