//! The memory projection of a step: the current string, the length of the
//! one before it and the limits in; a [`DeriveError::TooLarge`] out when
//! the next string, projected from the last step's growth, would not fit
//! in the memory available, so that the derivation fails at once with
//! the projected size instead of being killed by the system mid-step.

use super::error::DeriveError;
use super::store::ModuleStore;

/// Bytes per module head and per parameter value in a [`ModuleStore`].
const HEAD_BYTES: f64 = 4.0;
const PARAM_BYTES: f64 = 8.0;

/// The projected next string, in modules and parameter values, capped at
/// the limits (a step stops with `ModuleLimit` as soon as it passes them).
pub(crate) fn project(
    prev_len: usize,
    cur: &ModuleStore,
    max_modules: usize,
    max_params: usize,
) -> (f64, f64) {
    let growth = if prev_len > 0 {
        (cur.len() as f64 / prev_len as f64).max(1.0)
    } else {
        1.0
    };
    (
        (cur.len() as f64 * growth).min(max_modules as f64 + 1.0),
        (cur.param_count() as f64 * growth).min(max_params as f64 + 1.0),
    )
}

/// Fail when the string of step `step`, projected from `cur` and the
/// length of the string before it, would not fit beside `cur` in the
/// memory available (`available`: bytes, `None` when unknown).
pub(crate) fn check(
    prev_len: usize,
    cur: &ModuleStore,
    step: u32,
    (max_modules, max_params): (usize, usize),
    available: Option<u64>,
) -> Result<(), DeriveError> {
    let Some(avail) = available else {
        return Ok(());
    };
    let (mods, params) = project(prev_len, cur, max_modules, max_params);
    let next = mods * HEAD_BYTES + params * PARAM_BYTES;
    let now = cur.len() as f64 * HEAD_BYTES + cur.param_count() as f64 * PARAM_BYTES;
    if next + now <= avail as f64 {
        return Ok(());
    }
    Err(DeriveError::TooLarge {
        step,
        modules: mods as u64,
        bytes: gib(next + now),
        available: gib(avail as f64),
        limit: max_modules,
    })
}

fn gib(b: f64) -> String {
    format!("{:.1} GiB", b / (1u64 << 30) as f64)
}

/// Memory the system can still give (Linux `MemAvailable`); `None`
/// elsewhere or when unreadable, and then nothing is projected.
pub(crate) fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn string(n: usize, params: usize) -> ModuleStore {
        let mut s = ModuleStore::new();
        for i in 0..n {
            s.push(5, if i < params { &[1.0] } else { &[] });
        }
        s
    }

    #[test]
    fn projects_the_last_growth_capped_at_the_limits() {
        let s = string(1000, 500);
        assert_eq!(project(250, &s, 1_000_000, 1_000_000), (4000.0, 2000.0));
        assert_eq!(project(250, &s, 3000, 1_000_000), (3001.0, 2000.0));
        // A shrinking string is projected not to grow.
        assert_eq!(project(5000, &s, 1_000_000, 1_000_000), (1000.0, 500.0));
    }

    #[test]
    fn fails_when_the_next_string_would_not_fit() {
        let s = string(1000, 1000);
        // Now 12 kB, next 48 kB.
        assert!(check(250, &s, 3, (1 << 40, 1 << 40), Some(100_000)).is_ok());
        assert!(check(250, &s, 3, (1 << 40, 1 << 40), None).is_ok());
        let e = check(250, &s, 3, (1 << 40, 1 << 40), Some(50_000)).unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("step 3") && text.contains("4000 modules"),
            "{text}"
        );
        assert_eq!(e.step(), Some(3));
    }
}
