//! The ranges a Pailou's parameters may take: outside them the grammar
//! builds nothing an architect would recognise (a negative pillar height
//! sinks the gate into the ground, which the structural check then
//! reports part by part; 40 Toukung levels stack brackets far above the
//! roofs). Input: a define's name and value; output: `Err` with the
//! sentence the studio shows.

/// (name, lowest, highest, whole numbers only). Table 3's Pailous keep
/// ω at 9 or 10 and the ratios between 7/61 and 20/12; the ranges leave
/// room around them for design, not for nonsense.
const RANGES: &[(&str, f64, f64, bool)] = &[
    ("ω", 0.5, 100.0, false),
    ("NTL", 1.0, 12.0, true),
    ("TM.NTL", 1.0, 12.0, true),
    ("TS.NTL", 1.0, 12.0, true),
    ("αPW", 0.01, 2.0, false),
    ("αEW", 0.1, 5.0, false),
    ("αLH", 0.05, 2.0, false),
    ("αLW", 0.1, 3.0, false),
    ("αUp", 0.1, 2.0, false),
    ("αSide", 0.1, 2.0, false),
    ("κT", 0.02, 0.5, false),
    ("αRD", 0.1, 2.0, false),
    ("αRH", 0.05, 1.0, false),
];

/// A table's index ranges, lowest and highest, per dimension.
type Dims = &'static [(usize, usize)];

/// The per-entrance tables of the grammar (the entrance's ratios and its
/// components' sizes): name, the ratio whose range they take, and their
/// index ranges (docs/pailou.md, "Per entrance").
const TABLES: &[(&str, &str, Dims)] = &[
    ("up", "αUp", &[(1, 6), (2, 4)]),
    ("side", "αSide", &[(1, 5)]),
    ("pw", "αPW", &[(1, 6), (1, 4)]),
    ("lh", "αLH", &[(1, 6), (1, 4)]),
    ("lw", "αLW", &[(1, 6), (1, 4)]),
    ("tk", "κT", &[(1, 6), (1, 4)]),
    ("rd", "αRD", &[(1, 6), (1, 4)]),
    ("rh", "αRH", &[(1, 6), (1, 4)]),
];

/// `up[i,j]`, `side[i]`, `pw[i,j]`, ...: the ratio it is an entrance's value of, or the
/// sentence saying which indices the table has.
fn table_ratio(name: &str) -> Option<Result<&'static str, String>> {
    let (table, rest) = name.split_once('[')?;
    let &(t, ratio, dims) = TABLES.iter().find(|t| t.0 == table.trim())?;
    let wanted = || {
        let dims: Vec<String> = dims.iter().map(|(lo, hi)| format!("{lo}..{hi}")).collect();
        format!(
            "`{name}`: the entrance table `{t}` takes [{}] (docs/pailou.md, \"Per entrance\")",
            dims.join(", ")
        )
    };
    let indices: Vec<Option<usize>> = rest
        .strip_suffix(']')
        .unwrap_or("x")
        .split(',')
        .map(|n| n.trim().parse().ok())
        .collect();
    let fits = indices.len() == dims.len()
        && indices
            .iter()
            .zip(dims)
            .all(|(n, (lo, hi))| n.is_some_and(|n| (*lo..=*hi).contains(&n)));
    Some(if fits { Ok(ratio) } else { Err(wanted()) })
}

/// Whether `value` is a value `name` may take (names without a range may
/// take any finite value; an entrance's `up[i,j]`, `side[i]`, `pw[i,j]`,
/// ... take the range of the ratio they default to).
pub fn check(name: &str, value: f64) -> Result<(), String> {
    if !value.is_finite() {
        return Err(format!("`{name}` = {value} is not a number"));
    }
    let ratio = match table_ratio(name) {
        Some(Ok(ratio)) => ratio,
        Some(Err(why)) => return Err(why),
        None => name,
    };
    let Some(&(_, lo, hi, whole)) = RANGES.iter().find(|r| r.0 == ratio) else {
        return Ok(());
    };
    if whole && value.fract() != 0.0 {
        return Err(format!(
            "`{name}` counts levels: a whole number from {lo} to {hi}, not {value}"
        ));
    }
    if value < lo || value > hi {
        return Err(format!(
            "`{name}` = {value} is out of range: it goes from {lo} to {hi} (docs/pailou.md)"
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::check;

    #[test]
    fn the_paper_defaults_pass_and_the_absurd_do_not() {
        assert!(check("ω", 9.0).is_ok());
        assert!(check("NTL", 5.0).is_ok());
        assert!(check("αSide", 0.8).is_ok());
        assert!(check("ω", -5.0).is_err());
        assert!(check("NTL", 40.0).is_err());
        assert!(check("NTL", 4.5).is_err());
        assert!(check("κT", f64::NAN).is_err());
        assert!(check("κT", 0.3).is_ok());
        // An entrance's ratios: αUp's and αSide's ranges, at indices the
        // grammar's tables have (no up for a ground entrance).
        assert!(check("up[2,2]", 0.4).is_ok());
        assert!(check("up[2, 3]", 0.4).is_ok());
        assert!(check("side[1]", 0.7).is_ok());
        assert!(check("up[2,2]", 5.0).unwrap_err().contains("out of range"));
        assert!(check("up[2,1]", 0.4).unwrap_err().contains("[1..6, 2..4]"));
        assert!(check("up[2]", 0.4).is_err());
        assert!(check("side[6]", 0.7).is_err());
        assert!(check("side[x]", 0.7).is_err());
        // a component's size at an entrance takes its global ratio's range
        assert!(check("pw[2,1]", 0.16).is_ok());
        assert!(check("tk[1,2]", 0.16).is_ok());
        assert!(check("tk[1,2]", 3.0).unwrap_err().contains("0.02 to 0.5"));
        assert!(check("rh[7,1]", 0.3).unwrap_err().contains("1..6, 1..4"));
        assert!(check("αRD", -1.0).is_err());
    }
}
