//! Ridge ornaments: a band of the shape tree over the ridge -> whether it
//! holds the chiwen on the ridge's two ends (and nothing between), so the
//! recogniser can set it aside before it reads the ridge and the roof.

use super::super::regions::Region;
use super::super::tree::Node;

/// Whether `band` holds ridge ornaments: drawn at both ends of the
/// drawing's middle (something in its left and in its right half) and
/// over less than a fifth of the drawing's `width` in all.
pub(super) fn ornaments(band: &Node, width: i32, regions: &[Region]) -> bool {
    let mut spans: Vec<(i32, i32)> = band
        .regions
        .iter()
        .map(|&r| (regions[r].bbox[0], regions[r].bbox[2]))
        .collect();
    if spans.is_empty() {
        return false;
    }
    spans.sort_unstable();
    let (mut covered, mut end) = (0, i32::MIN);
    for (a, b) in &spans {
        covered += (b - a.max(&end)).max(0);
        end = end.max(*b);
    }
    let middle = band.bbox[0] + band.w() / 2;
    let left = spans.iter().any(|s| s.1 <= middle);
    let right = spans.iter().any(|s| s.0 >= middle);
    left && right && covered * 5 < width
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ridge ornaments: a band drawn only near both ends is ornaments; a
    /// ridge drawn across, a band drawn at one end only, or ornaments as
    /// wide as a fifth of the drawing are not.
    #[test]
    fn ornaments_are_drawn_at_both_ends_only() {
        let region = |x0: i32, x1: i32| Region {
            bbox: [x0, 0, x1, 8],
            area: 1,
        };
        let with = |spans: &[(i32, i32)]| {
            let regions: Vec<Region> = spans.iter().map(|&(a, b)| region(a, b)).collect();
            let mut b = super::super::placeholder();
            b.bbox = [0, 0, 100, 8];
            b.regions = (0..regions.len()).collect();
            ornaments(&b, 100, &regions)
        };
        assert!(with(&[(10, 14), (11, 13), (86, 90)]));
        assert!(!with(&[(10, 90)]), "a ridge");
        assert!(!with(&[(10, 14)]), "one end");
        assert!(!with(&[(10, 21), (80, 91)]), "22 of 100 drawn");
    }
}
