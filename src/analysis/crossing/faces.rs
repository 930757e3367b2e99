//! What a cell's points say about its surfaces: a face along the strip and the ground
//! beside it, a wall's fringe past the horizon, one surface sloping across the cell.

use super::ROUGH_SPREAD_M;
use crate::grid::Cell;
use nalgebra::Vector3;

/// Whether a cell past the horizon holds only the fringe of the face along its strip
/// that the strip's last seen cell showed (`wall`: that cell's x, top and top's y,
/// metres, the top the highest of the run of cells that showed it; x moved on to each
/// cut cell after it holding only that fringe). The cell's upper band is under
/// [`crate::grid::SURFACE_MIN_SHARE`] of its points (`crest` is `foot`), or centres
/// on the face's line too (the fringe is a surface of its own, but the floor's few
/// points, drawn toward the wall by noise, centre too close to it for
/// [`ground_beside_face`] to tell the two apart: `sweep -- families 100 5701 random`
/// #47, noisy, an 18 cm `step` 2.80 m out); it lies within [`WALL_REACH_M`] of that
/// x; its top stands no higher than the face's did (within rough ground's spread,
/// [`ROUGH_SPREAD_M`]); and its top voxel hugs the strip's side
/// ([`FACE_OFF_VOXELS`] off its centre line `y_mid`) on the face's line (within that
/// much of the face's top). Its top is then
/// the wall's, not a bound on the strip's ground: a trench's wall along the
/// corridor's edge, its top level with the ground beside the trench, ran on into the
/// cells the image's top edge cuts and made the floor "rise" to it (`sweep --
/// families 100 5401 random` #91, `oblique 100 5403` #44 noisy). Anything new there
/// still bounds the strip: a top higher than the wall's, off its line (a post
/// standing in the strip), or a surface across the cell.
pub(super) fn wall_goes_on(cell: &Cell, wall: Option<[f32; 3]>, y_mid: f32, vs: f32) -> bool {
    let side = FACE_OFF_VOXELS * vs;
    top_hugs_side(cell, y_mid, vs)
        && wall.is_some_and(|[x, top, top_y]| {
            let on_line = |y: f32| (y - top_y).abs() <= side;
            (cell.crest == cell.foot || on_line(cell.crest_xy[1]))
                && cell.x - x <= WALL_REACH_M
                && cell.top <= top + ROUGH_SPREAD_M
                && on_line(cell.top_xy[1])
        })
}

/// Whether a cell past the horizon shows nothing of the face along its strip seen
/// before (`wall`, as [`wall_goes_on`] takes it) and nothing that bounds the strip
/// over it: its top voxel lies off the strip's side (within [`FACE_OFF_VOXELS`] of its
/// centre line `y_mid`) and no higher than the face's top (within rough ground's
/// spread, [`ROUGH_SPREAD_M`]). The face may then run on past it, up to
/// [`WALL_REACH_M`] from the last cell that showed it: a cell the image's top corner
/// cuts to a few of the floor's points hides it, and the next cell's top, the fringe
/// of the outer ground's wall on the corridor's edge, stood 11 cm over the floor of a
/// one-track descent, a `step` (`sweep -- oblique 100 4203 random` #26, noisy).
pub(super) fn clear_of_wall(cell: &Cell, [_, top, _]: [f32; 3], y_mid: f32, vs: f32) -> bool {
    !top_hugs_side(cell, y_mid, vs) && cell.top <= top + ROUGH_SPREAD_M
}

/// Whether a cell seen whole holds the fringe of a face along its strip standing more
/// than a wheel radius `r` above its ground `z`: one surface (the face's points are
/// under [`crate::grid::SURFACE_MIN_SHARE`] of the cell's, `crest` is `foot`), and a
/// top over `z` by more than `r` whose voxel hugs the strip's side
/// ([`FACE_OFF_VOXELS`] off its centre line `y_mid`). Depth noise scatters a trench
/// wall's points on the corridor's edge over more voxel layers, so that in some of its
/// cells they no longer make a band of their own; the wall is still there, and the
/// cells the image's top edge cuts past it hold its fringe ([`wall_goes_on`]): without
/// it, their tops read as a rise of the floor (`sweep -- families 100 5606 random` #3,
/// noisy: a 16 cm `step` 2.35 m out).
pub(super) fn fringe_of_wall(cell: &Cell, z: f32, y_mid: f32, r: f32, vs: f32) -> bool {
    cell.crest == cell.foot && cell.top - z > r && top_hugs_side(cell, y_mid, vs)
}

/// Whether a cell's top voxel hugs its strip's side: [`FACE_OFF_VOXELS`] or more off
/// the strip's centre line `y_mid` (metres; `vs` the voxel size), where a face along
/// the strip or the ground beside it puts it, not a surface across the cell.
pub(super) fn top_hugs_side(cell: &Cell, y_mid: f32, vs: f32) -> bool {
    (cell.top_xy[1] - y_mid).abs() >= FACE_OFF_VOXELS * vs
}

/// The floor's height in a cell past the horizon that holds a wall's fringe
/// ([`wall_goes_on`]), metres: its lower surface, or, where `foot` is not one (it is
/// the cell's mean or its upper surface), its lowest voxel (a bound, and past the
/// horizon the lower one proves less). `foot` falls back to the mean when neither
/// band holds a surface (a tall face's points spread over so many voxel layers that
/// neither band holds a quarter of them), and to `crest` when only the upper band
/// does; either is then the face, not the floor. A one-track descent's 43 cm side
/// face on the corridor's edge, in the first cell the image's top edge cuts, read
/// 15 cm above the floor and made a `step` (`sweep -- oblique 100 5903` #57, the
/// mean); a 37 cm one, 30 cm above it (`oblique 100 6203` #66, the upper band). A
/// cell of one surface gives its mean for both too; its lowest voxel lies within a
/// voxel of it.
pub(super) fn floor_beside_fringe(cell: &Cell) -> f32 {
    if cell.foot == cell.z || cell.foot == cell.crest {
        cell.low.min(cell.foot)
    } else {
        cell.foot
    }
}

/// How far past the last cell that showed a face along the strip (or its fringe)
/// [`wall_goes_on`] takes it to run on, metres: three cells.
const WALL_REACH_M: f32 = 0.15;

/// In a cell with two surfaces, the ground when the face between them runs along the
/// strip: the face's points hug one side of the cell while the ground's spread across
/// it, so the surface whose points centre farther off the strip's centre line is the
/// face (the wall of a trench under the track, the side of a ramp beside the belly
/// band). `None` when the surfaces are close, or when they are offset more forward
/// than sideways (a face across the strip: a step, judged by the strip's course).
pub(crate) fn ground_beside_face(cell: &Cell, y_mid: f32, vs: f32) -> Option<f32> {
    if cell.crest - cell.foot < FACE_MIN_M {
        return None;
    }
    let dx = cell.crest_xy[0] - cell.foot_xy[0];
    let dy = cell.crest_xy[1] - cell.foot_xy[1];
    let off_crest = (cell.crest_xy[1] - y_mid).abs();
    let off_foot = (cell.foot_xy[1] - y_mid).abs();
    let (face, ground) = if off_crest > off_foot {
        (off_crest, off_foot)
    } else {
        (off_foot, off_crest)
    };
    if dy.abs() <= dx.abs() || face < FACE_OFF_VOXELS * vs || face - ground < SIDE_MIN_VOXELS * vs {
        return None;
    }
    Some(if off_crest < off_foot {
        cell.crest
    } else {
        cell.foot
    })
}

/// The ground of a cell holding a face along its strip that [`ground_beside_face`]
/// cannot resolve ([`unresolved_face_along`]): a face seen is turned to the camera,
/// so when its points hug the cell's side away from the camera the ground beyond
/// that side is higher and the cell's ground is its lowest voxel (a trench's wall on
/// the corridor's edge, whose points outnumber the floor's there so far that both of
/// the cell's bands lie on the wall); when they hug the side toward the camera, the
/// cell's ground is its highest voxel (a ramp's side beside the belly band). `None`
/// for any other cell, or when the camera is right above the strip.
///
/// For a cell [`ground_beside_face`] already gave nothing for.
pub(super) fn unresolved_ground(
    cell: &Cell,
    (x_mid, y_mid): (f32, f32),
    vs: f32,
    camera_y: f32,
) -> Option<f32> {
    let away = face_away(cell, (x_mid, y_mid), vs, camera_y)?;
    Some(if away { cell.low } else { cell.top })
}

/// For a cell [`unresolved_ground`] reads: whether its face hugs the side away from
/// the camera (`None` for a cell it does not read).
fn face_away(cell: &Cell, (x_mid, y_mid): (f32, f32), vs: f32, camera_y: f32) -> Option<bool> {
    if !hugs_one_side(cell, x_mid, y_mid, vs) || (camera_y - y_mid).abs() <= 0.5 * vs {
        return None;
    }
    Some((cell.y - y_mid).signum() != (camera_y - y_mid).signum())
}

/// Whether a cell [`unresolved_ground`] reads at its lowest voxel (its face hugs the
/// side away from the camera) shows none of its ground: its lower band centres as far
/// to that side as all its points do (within [`ON_FACE_M`]). Ground points, the lowest
/// of the cell's, would draw the lower band toward the strip's centre line more than
/// they draw the mean. Its lowest voxel is then the face's, and only an upper bound
/// on the ground: a one-track descent's outer wall on the corridor's edge, 2.8 m out
/// and seen by a 320×240 camera, held all of one cell's points, its floor between
/// two rows of pixels, and read 10 cm over the floor before and after it, a `step`
/// (`sweep -- oblique 100 5103 random` #38, clean).
pub(super) fn ground_unseen_beside_face(
    cell: &Cell,
    (x_mid, y_mid): (f32, f32),
    vs: f32,
    camera_y: f32,
) -> bool {
    ground_beside_face(cell, y_mid, vs).is_none()
        && face_away(cell, (x_mid, y_mid), vs, camera_y) == Some(true)
        && cell.foot != cell.crest
        && (cell.foot_xy[1] - y_mid).abs() + ON_FACE_M >= (cell.y - y_mid).abs()
}

/// Whether a cell's points span [`FACE_MIN_M`] or more: two levels (a face, or a
/// surface sloping steeply across the cell), not one surface seen whole.
pub(super) fn two_levels(cell: &Cell) -> bool {
    cell.top - cell.low >= FACE_MIN_M
}

/// Whether a cell holds a face along its strip whose ground its two surfaces do not
/// give: its points span more than [`FACE_MIN_M`] and hug one side of the cell
/// (their mean off the strip's centre line by [`FACE_OFF_VOXELS`], and off the row's
/// by at most half that: a face along the strip, not a corner of one across it), but
/// [`ground_beside_face`] cannot tell the bands apart. Its mean height
/// belongs to neither the ground nor the face's other side. `x_mid`, `y_mid`: the
/// cell's centre, metres.
pub(crate) fn unresolved_face_along(cell: &Cell, x_mid: f32, y_mid: f32, vs: f32) -> bool {
    hugs_one_side(cell, x_mid, y_mid, vs) && ground_beside_face(cell, y_mid, vs).is_none()
}

/// The side test of [`unresolved_face_along`], without the band test.
fn hugs_one_side(cell: &Cell, x_mid: f32, y_mid: f32, vs: f32) -> bool {
    let off_y = (cell.y - y_mid).abs();
    two_levels(cell)
        && off_y >= FACE_OFF_VOXELS * vs
        && (cell.x - x_mid).abs() <= 0.5 * FACE_OFF_VOXELS * vs
}

/// Whether a cell holds one surface sloping across its strip, not two surfaces with a
/// face between: its points span more than [`FACE_MIN_M`], spread evenly across the
/// cell (their mean within [`SPREAD_OFF_VOXELS`] of the strip's centre line `y_mid`:
/// a face's points pull it toward the cell's side) and over their span (their mean
/// height within [`SPREAD_MID_SHARE`] of its middle: a flat surface beside a face
/// pulls it toward that surface); its upper and lower bands centre on opposite sides
/// of the points' mean, apart more sideways than forward (a face across the strip
/// parts them forward) by at least [`SIDE_MIN_VOXELS`]; or, when only one band holds
/// a surface, its top voxel lies to one side, by half [`FACE_OFF_VOXELS`] off both the
/// points' mean and the strip's centre line, and farther sideways of the points' mean
/// than forward (a surface sloping across has its highest points on its high side; a
/// ramp's top spread across the cell has its top voxel on the centre line, however far
/// a side face's points on the cell's edge pull the mean: `sweep -- natural 100 7102
/// random` #9; a ramp rising along the strip has it at the cell's far end, off the
/// line only by where a rolled camera's last row crosses the cell: `natural 100 9902
/// random` #86, 2.4 cm forward and 1.8 cm aside). The cell's
/// mean height is then the ground's on the strip's centre line (exact for a plane).
pub(super) fn slopes_across(cell: &Cell, y_mid: f32, vs: f32) -> bool {
    let span = cell.top - cell.low;
    if span < FACE_MIN_M
        || (cell.y - y_mid).abs() > SPREAD_OFF_VOXELS * vs
        || (cell.z - 0.5 * (cell.top + cell.low)).abs() > SPREAD_MID_SHARE * span
    {
        return false;
    }
    if cell.crest == cell.foot {
        let off = |y: f32| (cell.top_xy[1] - y).abs() >= TOP_OFF_VOXELS * vs;
        let aside = (cell.top_xy[1] - cell.y).abs() > (cell.top_xy[0] - cell.x).abs();
        return off(cell.y) && off(y_mid) && aside;
    }
    let (dx, dy) = (
        cell.crest_xy[0] - cell.foot_xy[0],
        cell.crest_xy[1] - cell.foot_xy[1],
    );
    (cell.crest_xy[1] - cell.y) * (cell.foot_xy[1] - cell.y) < 0.0
        && dy.abs() > dx.abs()
        && dy.abs() >= SIDE_MIN_VOXELS * vs
}

/// Whether a cell's two bands ([`Cell::crest`], [`Cell::foot`]) could not be one surface
/// sloping across its strip as the camera at `camera` (rover frame, metres) sees it:
/// the line of sight to the upper band meets the surface joining them under
/// [`LIP_SIGHT_DEG`], or from behind. The bands then lie on one line of sight: a lip
/// and the first ground seen past its shadow (or a face's top and foot seen edge-on),
/// not the two sides of one slope, and the cell's mean belongs to neither. Ground
/// falling away 27 cm beside a track's inner edge put two of the belly's points at
/// its lip into the track's edge strip, 2.5 m out, over two of the descent's just past
/// the lip's shadow on the strip's far side: read as a slope across, seen at 0.1°, its
/// mean stood 13 cm over the descent before it, a `step` (`sweep -- families 100 11611
/// random 2` #31, noisy). A steep slope seen grazingly still gives points between its
/// bands: a half-plane descent's 77° edge, 2.8 m out, met at 3.7-5.7°, is read across
/// (`bevelled 100 7506 random` #13, noisy; at [`GRAZING_DEG`](super::GRAZING_DEG) it
/// was a `step`). For a cell with one band, `false`.
pub(super) fn lip_over_shadow(cell: &Cell, camera: [f32; 3]) -> bool {
    let dy = cell.crest_xy[1] - cell.foot_xy[1];
    if cell.crest == cell.foot || dy == 0.0 {
        return false;
    }
    // The joining surface's upward normal (it runs along x), and the line of sight.
    let normal = Vector3::new(0.0, -(cell.crest - cell.foot), dy) * dy.signum();
    let sight = Vector3::new(
        cell.crest_xy[0] - camera[0],
        cell.crest_xy[1] - camera[1],
        cell.crest - camera[2],
    );
    let sin_seen = -sight.dot(&normal) / (sight.norm() * normal.norm());
    sin_seen < LIP_SIGHT_DEG.to_radians().sin()
}

/// How steeply a cell that [`slopes_across`] its strip slopes across it, metres per
/// metre of y (positive when it rises to the left): from its two bands' heights and
/// centres, or with one band, from its top voxel over the points' mean. `None` when
/// they lie too close sideways to give a slope (under [`TOP_OFF_VOXELS`], the least
/// [`slopes_across`] asks of a top voxel).
pub(super) fn cross_slope(cell: &Cell, vs: f32) -> Option<f32> {
    let ((z_a, y_a), (z_b, y_b)) = if cell.crest == cell.foot {
        ((cell.top, cell.top_xy[1]), (cell.z, cell.y))
    } else {
        ((cell.crest, cell.crest_xy[1]), (cell.foot, cell.foot_xy[1]))
    };
    let dy = y_a - y_b;
    (dy.abs() >= TOP_OFF_VOXELS * vs).then(|| (z_a - z_b) / dy)
}

/// The height on the strip's centre line `y_mid` of a cell whose one surface lies on
/// one side of it (its points' mean off the line by more than [`SPREAD_OFF_VOXELS`]),
/// in a strip read along a surface sloping across it at `cross` ([`cross_slope`] of
/// the last cell read so): its mean carried to the centre line along that slope,
/// metres. `None` for a cell with two surfaces, or one spread across it.
///
/// Far out, the camera meets a ramp's or a descent's side at a few degrees: the
/// cells of the track's edge strip there get a handful of points, and some only on
/// the strip's low side. Read as the strip's ground, their mean stood 12 cm below the
/// cells before (the strip's centre line on the side), a `step` 2.8 m out on a
/// half-plane descent whose side fades over 10 cm (`sweep -- bevelled 100 7506
/// random` #13, noisy).
pub(super) fn beside_slope(cell: &Cell, y_mid: f32, cross: f32, vs: f32) -> Option<f32> {
    let off = cell.y - y_mid;
    (cell.crest == cell.foot && !two_levels(cell) && off.abs() > SPREAD_OFF_VOXELS * vs)
        .then_some(cell.z - off * cross)
}

/// Most sideways offset of the mean of a cell's points from the strip's centre line
/// for [`slopes_across`], voxels: a ramp's sloping side put it within 0.1 of a voxel,
/// a vertical side's points beside the ramp's top 0.13-0.3 (`sweep -- families 100
/// 5501 random` #99 and #97; where they pull it less, the height test tells).
const SPREAD_OFF_VOXELS: f32 = 0.15;
/// Most offset of a cell's mean height from the middle of its span for
/// [`slopes_across`], a share of the span: up to 0.13 on a ramp's sloping side (the
/// voxel layers move its top and low), 0.23-0.33 on a ramp's top beside its vertical
/// side (#97, #99).
const SPREAD_MID_SHARE: f32 = 0.2;

/// How much nearer the strip's centre line than all its points a cell's lower band may
/// centre and still lie on the face ([`ground_unseen_beside_face`]), metres: float
/// rounding, not a ground point's pull.
const ON_FACE_M: f32 = 0.001;
/// Least height between a cell's two surfaces for [`ground_beside_face`] to tell
/// them apart (and for the test of climbs the view ends in to read a belly cell at its
/// top), metres: above rough ground's spread within one cell.
pub(super) const FACE_MIN_M: f32 = 0.04;
/// Below this angle, degrees, the line of sight to a cell's upper band runs along the
/// surface that would join its two bands ([`lip_over_shadow`]): they lie on one line of
/// sight, which a slope would not leave them on.
const LIP_SIGHT_DEG: f32 = 1.0;
/// Least sideways offset of a face's points from the strip's centre line for
/// [`ground_beside_face`], voxels: a face hugs the cell's side (0.5), a surface spread
/// across the cell centres on it (0), whatever the noise.
pub(super) const FACE_OFF_VOXELS: f32 = 0.3;
/// Least sideways distance, voxels, of a one-band cell's top voxel from its points'
/// mean and from the strip's centre line for [`slopes_across`], and of the two heights
/// [`cross_slope`] takes a slope from: half [`FACE_OFF_VOXELS`].
const TOP_OFF_VOXELS: f32 = 0.5 * FACE_OFF_VOXELS;
/// Least difference of the two surfaces' sideways offsets for [`ground_beside_face`],
/// voxels.
const SIDE_MIN_VOXELS: f32 = 0.2;

#[cfg(test)]
mod tests {
    use super::*;

    /// A cell centred at (1.025, 0.675) with the given surfaces and their centroids.
    fn cell(crest: f32, crest_xy: [f32; 2], foot: f32, foot_xy: [f32; 2]) -> Cell {
        Cell {
            n: 100,
            x: 1.025,
            y: 0.675,
            z: 0.5 * (crest + foot),
            top: crest,
            peak: crest,
            top_xy: crest_xy,
            low: foot,
            crest,
            foot,
            crest_xy,
            foot_xy,
        }
    }

    const VS: f32 = 0.05;
    const MID: f32 = 0.675;

    #[test]
    fn a_cell_whose_one_surface_slopes_across_reads_its_mean_but_a_face_beside_ground_does_not() {
        // A ramp's side sloping across the cell, 0.5 to 0.95 of its 39 cm height over
        // its width (`sweep -- bevelled 60 904 default 0` #24, 1.525 m): the points
        // spread evenly, the bands lie either side of the middle.
        let mut c = cell(0.331, [1.026, MID - 0.014], 0.214, [1.024, MID + 0.016]);
        (c.z, c.top, c.low, c.top_xy) = (0.274, 0.354, 0.187, [1.038, MID - 0.020]);
        assert!(slopes_across(&c, MID, VS));
        // The same with too few points in its lower band for a surface: one band.
        let mut one = c;
        (one.foot, one.foot_xy) = (one.crest, one.crest_xy);
        assert!(slopes_across(&one, MID, VS));
        // The mean pulled toward the top: a flat surface with a vertical face's points
        // beside it (the ramp's top and its sharp side, `families 100 5501 random` #97).
        let mut face = one;
        (face.z, face.low) = (0.325, 0.03);
        assert!(!slopes_across(&face, MID, VS));
        // One band whose top voxel lies on the strip's centre line: a ramp's top
        // spread across the cell, the mean pulled 0.14 of a voxel to its side by a
        // vertical side face's points on the cell's edge (`sweep -- natural 100 7102
        // random` #9, the right track's inner strip, y from −0.25 to −0.2, 2.675 m
        // out; to the millimetre). The top voxel lies 0.16 of a voxel off the mean
        // only because the mean moved: read as a slope across, the strip took the
        // mean, 4 cm under the ramp, and then climbed back to it: a `step`.
        let edge = Cell {
            n: 30,
            x: 2.675,
            y: -0.218,
            z: 0.321,
            top: 0.366,
            peak: 0.366,
            top_xy: [2.675, -0.226],
            low: 0.275,
            crest: 0.362,
            foot: 0.362,
            crest_xy: [2.676, -0.223],
            foot_xy: [2.676, -0.223],
        };
        assert!(!slopes_across(&edge, -0.225, VS));
        // Its top voxel on one side, off the centre line too: a slope across.
        let sloped = Cell {
            top_xy: [2.675, -0.235],
            ..edge
        };
        assert!(slopes_across(&sloped, -0.225, VS));
        // Its top voxel off the centre line, but farther forward than sideways: a ramp
        // rising along the strip, whose highest points lie at the cell's far end, seen
        // by a rolled camera whose last row across the cell runs aslant (`sweep --
        // natural 100 9902 random` #86, the right track's inner strip, 2.525 m out, to
        // the millimetre). Read as a slope across, the strip took the mean, 5 cm under
        // the ramp, kept to the means for seven cells and climbed back: a `slope`.
        let aslant = Cell {
            n: 33,
            x: 2.525,
            y: -0.219,
            z: 0.435,
            top: 0.500,
            peak: 0.501,
            top_xy: [2.549, -0.237],
            low: 0.330,
            crest: 0.489,
            foot: 0.489,
            crest_xy: [2.524, -0.224],
            foot_xy: [2.524, -0.224],
        };
        assert!(!slopes_across(&aslant, -0.225, VS));
        // The same top voxel at the cell's middle in x: sideways only, a slope across.
        let across = Cell {
            top_xy: [2.530, -0.237],
            ..aslant
        };
        assert!(slopes_across(&across, -0.225, VS));
        // The points' mean off the middle: a face hugging the cell's side.
        let mut hug = c;
        hug.y = MID + 0.01;
        assert!(!slopes_across(&hug, MID, VS));
        // The bands apart forward rather than sideways: a face across the strip.
        let mut step = c;
        (step.crest_xy, step.foot_xy) = ([1.045, MID - 0.005], [1.005, MID + 0.005]);
        assert!(!slopes_across(&step, MID, VS));
        // Within rough ground's spread: no slope to read.
        let mut flat = c;
        flat.top = flat.low + 0.03;
        assert!(!slopes_across(&flat, MID, VS));
    }

    #[test]
    fn bands_a_slope_across_would_join_out_of_the_camera_s_sight_are_a_lip_and_its_shadow() {
        // Ground falling away 27 cm beside the right track's inner edge, 2.5 m out
        // (`sweep -- families 100 11611 random 2` #31, noisy, the edge strip from
        // y = −0.25 to −0.2, to the millimetre): two of the belly's points at the lip,
        // two of the descent's past the lip's shadow. The camera, 0.64 m high, looks
        // over the lip at 80.8° across the strip; a surface joining the bands falls
        // away at 80.3°, seen at 0.1°.
        let camera = [0.2549, -0.0957, 0.6448];
        let lip = Cell {
            n: 4,
            x: 2.535,
            y: -0.224,
            z: -0.141,
            top: -0.006,
            peak: -0.006,
            top_xy: [2.540, -0.201],
            low: -0.276,
            crest: -0.006,
            foot: -0.276,
            crest_xy: [2.540, -0.201],
            foot_xy: [2.531, -0.247],
        };
        assert!(slopes_across(&lip, -0.225, VS));
        assert!(lip_over_shadow(&lip, camera));
        // A bevel falling away at 45° over the same strip is seen at 9°: one slope.
        let bevel = Cell {
            z: -0.02,
            top: 0.0,
            peak: 0.0,
            low: -0.04,
            crest: 0.0,
            foot: -0.04,
            top_xy: [2.540, -0.205],
            crest_xy: [2.540, -0.205],
            foot_xy: [2.531, -0.245],
            ..lip
        };
        assert!(!lip_over_shadow(&bevel, camera));
        // A half-plane descent's 77° edge 2.8 m out, seen from 1.15 m high at 3.7°
        // (`sweep -- bevelled 100 7506 random` #13, noisy, to the 0.1 mm): five points
        // spread over it, one slope.
        let grazed = Cell {
            n: 5,
            x: 2.7656,
            y: 0.2246,
            z: -0.3053,
            top: -0.2380,
            peak: -0.2327,
            top_xy: [2.7648, 0.2087],
            low: -0.4062,
            crest: -0.2380,
            foot: -0.4062,
            crest_xy: [2.7648, 0.2087],
            foot_xy: [2.7669, 0.2483],
        };
        assert!(slopes_across(&grazed, 0.225, VS));
        assert!(!lip_over_shadow(&grazed, [0.2180, 0.0737, 1.1504]));
        // The lip's bands seen from across the strip: a face rising away, seen well.
        assert!(!lip_over_shadow(&lip, [0.2549, -0.6, 0.6448]));
        // One band: nothing to join.
        let one = Cell {
            foot: lip.crest,
            foot_xy: lip.crest_xy,
            ..lip
        };
        assert!(!lip_over_shadow(&one, camera));
    }

    #[test]
    fn a_cell_seeing_only_the_low_side_of_a_slope_across_is_read_on_the_centre_line() {
        // A half-plane descent's edge sloping 77° across the left track's edge strip
        // (y from 0.2 to 0.25), 2.77 m out (`sweep -- bevelled 100 7506 random` #13,
        // noisy; to the millimetre): two bands 17 cm apart, 3.9 cm apart sideways.
        let mid = 0.225;
        let side = Cell {
            n: 5,
            x: 2.766,
            y: 0.225,
            z: -0.305,
            top: -0.238,
            peak: -0.233,
            top_xy: [2.765, 0.209],
            low: -0.406,
            crest: -0.238,
            foot: -0.406,
            crest_xy: [2.765, 0.209],
            foot_xy: [2.767, 0.248],
        };
        let k = cross_slope(&side, VS).unwrap();
        assert!((k - (-0.238 + 0.406) / (0.209 - 0.248)).abs() < 1e-4, "{k}");
        // The next cell's three points, all on the strip's low side, 12 cm under it.
        let low_side = Cell {
            n: 3,
            x: 2.827,
            y: 0.249,
            z: -0.422,
            top: -0.422,
            peak: -0.416,
            top_xy: [2.827, 0.249],
            low: -0.422,
            crest: -0.422,
            foot: -0.422,
            crest_xy: [2.827, 0.249],
            foot_xy: [2.827, 0.249],
        };
        let z = beside_slope(&low_side, mid, k, VS).unwrap();
        assert!(
            (z - (-0.422 - 0.024 * k)).abs() < 1e-4 && (z - side.z).abs() < 0.03,
            "{z}"
        );
        // Points spread across the strip, or two surfaces: read as they are.
        let centred = Cell {
            y: mid + 0.005,
            ..low_side
        };
        assert_eq!(beside_slope(&centred, mid, k, VS), None);
        assert_eq!(beside_slope(&side, mid, k, VS), None);
        // Bands one above the other (a face across the strip): no slope across.
        let step = Cell {
            crest_xy: [2.78, 0.226],
            foot_xy: [2.75, 0.224],
            ..side
        };
        assert_eq!(cross_slope(&step, VS), None);
    }

    #[test]
    fn a_wall_along_the_strip_leaves_the_floor_as_ground() {
        // A trench's outer wall at y = 0.7: its points (the crest) hug the side.
        let c = cell(-0.05, [1.025, 0.698], -0.20, [1.025, 0.680]);
        assert_eq!(ground_beside_face(&c, MID, VS), Some(-0.20));
        // A ramp's side face at the cell's inner edge: the foot hugs the side.
        let c = cell(0.30, [1.025, 0.676], 0.12, [1.025, 0.652]);
        assert_eq!(ground_beside_face(&c, MID, VS), Some(0.30));
    }

    #[test]
    fn a_face_across_the_strip_or_close_surfaces_are_left_to_the_strip() {
        // A step's face: the crest lies behind the foot, not beside it.
        let c = cell(0.15, [1.040, 0.690], 0.0, [1.008, 0.675]);
        assert_eq!(ground_beside_face(&c, MID, VS), None);
        // Rough ground: two bands 3 cm apart are one surface.
        let c = cell(0.02, [1.025, 0.699], -0.01, [1.025, 0.675]);
        assert_eq!(ground_beside_face(&c, MID, VS), None);
        // Both bands spread across the cell: no side to hug.
        let c = cell(0.10, [1.025, 0.682], 0.0, [1.025, 0.672]);
        assert_eq!(ground_beside_face(&c, MID, VS), None);
    }

    #[test]
    fn a_seen_cell_shows_a_wall_by_its_top_alone_only_at_the_strips_side() {
        // One surface, the floor 22 cm under the belly's level; the wall's points too
        // few for a band of their own, its top voxel at the strip's side.
        let floor = |top: f32, top_y: f32| Cell {
            top,
            top_xy: [1.025, top_y],
            ..cell(-0.22, [1.025, 0.675], -0.22, [1.025, 0.675])
        };
        let r = 0.11;
        assert!(fringe_of_wall(&floor(0.0, 0.698), -0.22, MID, r, VS));
        // A top a wheel radius or less over the floor, or on the strip's centre line.
        assert!(!fringe_of_wall(&floor(-0.12, 0.698), -0.22, MID, r, VS));
        assert!(!fringe_of_wall(&floor(0.0, 0.68), -0.22, MID, r, VS));
        // Two surfaces: the wall is one of its own, judged by ground_beside_face.
        let two = cell(-0.05, [1.025, 0.698], -0.20, [1.025, 0.680]);
        assert!(!fringe_of_wall(&two, -0.20, MID, r, VS));
    }

    #[test]
    fn a_cut_cell_reads_as_the_wall_only_where_its_top_runs_on_along_the_wall() {
        // The strip's last seen cell: the wall at y = 0.7, its top at 0 over a floor
        // 22 cm down, 5 cm back.
        let wall = Some([0.975, 0.0, 0.699]);
        // A cut cell of floor whose top (too few points for a surface) is the wall's.
        let floor = |top: f32, top_y: f32| Cell {
            top,
            top_xy: [1.025, top_y],
            ..cell(-0.22, [1.025, 0.675], -0.22, [1.025, 0.675])
        };
        assert!(wall_goes_on(&floor(-0.03, 0.697), wall, MID, VS));
        // Noise-lifted by up to rough ground's spread, still the wall.
        assert!(wall_goes_on(&floor(0.012, 0.697), wall, MID, VS));
        // Higher than the wall: something new stands there.
        assert!(!wall_goes_on(&floor(0.03, 0.697), wall, MID, VS));
        // A top on the strip's centre line or off the wall's line: a post in the strip.
        assert!(!wall_goes_on(&floor(-0.05, 0.675), wall, MID, VS));
        assert!(!wall_goes_on(&floor(-0.05, 0.652), wall, MID, VS));
        // No wall before it, or the wall seen too far back.
        assert!(!wall_goes_on(&floor(-0.03, 0.697), None, MID, VS));
        assert!(!wall_goes_on(
            &floor(-0.03, 0.697),
            Some([0.8, 0.0, 0.699]),
            MID,
            VS
        ));
        // An upper band with points enough to be a surface is judged as one.
        let surface = Cell {
            top: -0.03,
            top_xy: [1.025, 0.697],
            ..cell(-0.05, [1.045, 0.675], -0.22, [1.010, 0.675])
        };
        assert!(!wall_goes_on(&surface, wall, MID, VS));
        // An upper band on the wall's line is the wall's fringe, over the floor, even
        // where the floor's points centre too near the wall for the two to be told
        // apart as a face and the ground beside it.
        let fringe = |crest_y: f32| Cell {
            top: -0.03,
            top_xy: [1.025, 0.697],
            ..cell(-0.05, [1.020, crest_y], -0.20, [1.023, 0.688])
        };
        assert_eq!(ground_beside_face(&fringe(0.697), MID, VS), None);
        assert!(wall_goes_on(&fringe(0.697), wall, MID, VS));
        assert!(!wall_goes_on(&fringe(0.680), wall, MID, VS));
    }

    #[test]
    fn a_wall_cell_whose_lower_band_lies_on_the_wall_shows_no_ground() {
        // The outermost strip of the right track, a descent's outer wall on the
        // corridor's edge (y = -0.7), the camera 0.085 m right of the centre line
        // (`sweep -- oblique 100 5103 random` #38, clean, 2.78 m out, to the
        // millimetre): every point on the wall, the lowest 10 cm over the floor.
        let (mid, camera_y) = ((2.775, -0.675), -0.085);
        let wall = Cell {
            n: 22,
            x: 2.777,
            y: -0.700,
            z: -0.172,
            top: -0.067,
            peak: -0.052,
            top_xy: [2.779, -0.700],
            low: -0.275,
            crest: -0.095,
            foot: -0.249,
            crest_xy: [2.778, -0.700],
            foot_xy: [2.771, -0.700],
        };
        assert_eq!(unresolved_ground(&wall, mid, VS, camera_y), Some(-0.275));
        assert!(ground_unseen_beside_face(&wall, mid, VS, camera_y));
        // The cell before it: a few floor points draw its lower band 9 mm off the
        // wall, more than they draw the mean; its lowest voxel is the floor.
        let floor = Cell {
            x: 2.677,
            y: -0.696,
            low: -0.344,
            foot: -0.308,
            foot_xy: [2.681, -0.691],
            ..wall
        };
        let before = (2.675, -0.675);
        assert!(!ground_unseen_beside_face(&floor, before, VS, camera_y));
        // The same points with the camera beyond them: they hug the side toward it,
        // and the cell reads its top (a ramp's side beside the belly band).
        assert!(!ground_unseen_beside_face(&wall, mid, VS, -0.9));
        // One band only: no lower band to say where the floor is.
        let one = Cell {
            foot: wall.crest,
            foot_xy: wall.crest_xy,
            ..wall
        };
        assert!(!ground_unseen_beside_face(&one, mid, VS, camera_y));
    }
}
