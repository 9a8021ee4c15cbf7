//! The painting session's placement: views, configure rules, correction,
//! reshaping, holes and refusals.

use super::*;

fn palette_() -> Vec<Component> {
    palette(&[
        ("H".into(), 3.0),
        ("DEPTH_Wall".into(), 0.5),
        ("DEPTH_Window".into(), 0.25),
        ("THROUGH_Window".into(), 1.0),
        ("DEPTH_Porch".into(), 2.0),
    ])
}

#[test]
fn the_palette_is_the_depth_defines() {
    let p = palette_();
    let names: Vec<(&str, bool)> = p.iter().map(|c| (c.name.as_str(), c.through)).collect();
    assert_eq!(names, [("Wall", false), ("Window", true), ("Porch", false)]);
}

#[test]
fn each_view_sees_the_same_box_from_its_side() {
    let p = Part {
        component: "Wall".into(),
        view: PaintView::Front,
        min: [1.0, 2.0, 3.0],
        max: [4.0, 6.0, 8.0],
    };
    assert_eq!(p.rect(PaintView::Front), [1.0, 2.0, 4.0, 6.0]);
    assert_eq!(p.rect(PaintView::Back), [-4.0, 2.0, -1.0, 6.0]);
    assert_eq!(p.rect(PaintView::Top), [1.0, -8.0, 4.0, -3.0]);
    assert_eq!(p.rect(PaintView::Left), [3.0, 2.0, 8.0, 6.0]);
    assert_eq!(p.rect(PaintView::Right), [-8.0, 2.0, -3.0, 6.0]);
}

#[test]
fn a_window_takes_the_walls_depth_and_snaps_to_its_edge() {
    let pal = palette_();
    let (wall, _) = front(&[], [0.0, 0.0, 6.0, 3.0], "Wall", 0.2, None).unwrap();
    assert_eq!((wall.min, wall.max), ([0.0, 0.0, 0.0], [6.0, 3.0, 0.5]));
    // Painted 0.15 short of the wall's top: the correction moves it up.
    let (win, how) = front(
        std::slice::from_ref(&wall),
        [1.0, 1.0, 2.0, 2.85],
        "Window",
        0.2,
        None,
    )
    .unwrap();
    assert_eq!((win.min, win.max), ([1.0, 1.0, 0.25], [2.0, 3.0, 0.5]));
    assert_eq!(
        how.corrections,
        ["its top edge moved by 0.15 to meet Wall 1's top edge"]
    );
    assert_eq!(
        how.depth,
        "0.25 into Wall 1 from its face (DEPTH_Window, THROUGH_Window)"
    );
    assert_eq!(
        holes(&[wall.clone(), win.clone()], &pal),
        ["Window 2 intersects Wall 1: a hole 1 x 2 is cut through it"]
    );
    // Threshold 0.1: no correction.
    let (win, how) = front(
        std::slice::from_ref(&wall),
        [1.0, 1.0, 2.0, 2.85],
        "Window",
        0.1,
        None,
    )
    .unwrap();
    assert_eq!(win.max[1], 2.85);
    assert!(how.corrections.is_empty());
    // A porch painted on the wall stands in front of it.
    let (porch, _) = front(&[wall], [1.0, 0.0, 5.0, 1.0], "Porch", 0.0, None).unwrap();
    assert_eq!((porch.min[2], porch.max[2]), (0.5, 2.5));
    // A window over the porch goes into the porch, or into the wall
    // when the user chose it.
    let two = [wall_(), porch.clone()];
    let (win, _) = front(&two, [2.0, 0.2, 3.0, 0.8], "Window", 0.0, None).unwrap();
    assert_eq!((win.min[2], win.max[2]), (2.25, 2.5));
    let (win, how) = front(&two, [2.0, 0.2, 3.0, 0.8], "Window", 0.0, Some(0)).unwrap();
    assert_eq!((win.min[2], win.max[2]), (0.25, 0.5));
    assert_eq!(
        how.depth,
        "0.25 into Wall 1 from its face (DEPTH_Window, THROUGH_Window)"
    );
    // A roof painted above the wall, 0.1 above its top: corrected onto
    // it, and as deep as the wall it stands on.
    let (roof, how) = front(&[wall_()], [-0.5, 3.1, 6.5, 5.0], "Porch", 0.2, None).unwrap();
    assert_eq!((roof.min, roof.max), ([-0.5, 3.0, 0.0], [6.5, 5.0, 0.5]));
    assert_eq!(how.depth, "as deep as Wall 1, which it stands on");
}

/// Paints in the front view with the test palette.
fn front(
    parts: &[Part],
    rect: [f64; 4],
    c: &str,
    t: f64,
    on: Option<usize>,
) -> Result<(Part, Painted), PaintError> {
    paint(parts, &palette_(), PaintView::Front, rect, c, t, on)
}

fn wall_() -> Part {
    Part {
        component: "Wall".into(),
        view: PaintView::Front,
        min: [0.0; 3],
        max: [6.0, 3.0, 0.5],
    }
}

#[test]
fn a_rectangle_from_another_view_gives_the_depth() {
    let (wall, _) = front(&[], [0.0, 0.0, 6.0, 3.0], "Wall", 0.0, None).unwrap();
    let (w, _) = reshape(&[wall], 0, PaintView::Left, [-1.0, 0.0, 4.0, 3.5], 0.0).unwrap();
    assert_eq!((w.min, w.max), ([0.0, 0.0, -1.0], [6.0, 3.5, 4.0]));
}

#[test]
fn bad_rectangles_and_components_are_refused() {
    let small = front(&[], [0.0, 0.0, 0.001, 3.0], "Wall", 0.0, None);
    assert!(matches!(small, Err(PaintError::Small { .. })));
    let far = front(&[], [0.0, 0.0, f64::NAN, 3.0], "Wall", 0.0, None);
    assert!(matches!(far, Err(PaintError::Far { .. })));
    let none = front(&[], [0.0, 0.0, 1.0, 3.0], "Tower", 0.0, None);
    assert!(matches!(none, Err(PaintError::Component { .. })));
}
