//! A solid's mesh held to its own report: what the command line promises (a result that is not
//! a closed 2-manifold is never passed on as if it were), for library callers.

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::solid::Solid;

/// How far a solid's mesh may bound a different volume than its polygons, as a part of the
/// larger of the two: the needle pass may change it by 10⁻² (see `mesh::needles`), twice that
/// for room. Far below what a lost or inside-out shell changes (a tiny cube at a unit cube's
/// corner gave 0.667 for 1).
pub const MESH_VOLUME_RELATIVE: f64 = 2e-2;

/// How far a solid's mesh may bound a different volume than its polygons, in tolerances times
/// the polygons' area: the weld moves corners by up to 8 tolerances and a wider one may sweep
/// four times that, thin shells within the weld are dropped, and the needle pass may change 32
/// more; 128 for room. (The needle pass counts in tolerances of the mesh's own size, up to 16
/// of these where the mesh is far larger than the region the operands met in: there a thin
/// result could pass this bound by the needle pass alone. None in the suite or the
/// cross-check comes near it.)
pub const MESH_VOLUME_TOLERANCES: f64 = 128.0;

impl Solid {
    /// Checks that `mesh`, this solid's [`Solid::to_mesh`] (a closed 2-manifold or empty),
    /// bounds the volume the solid's polygons do: the two may differ by at most
    /// [`MESH_VOLUME_RELATIVE`] of the larger, plus [`MESH_VOLUME_TOLERANCES`] tolerances times
    /// the polygons' area, plus what the polygons' own volume is unsure of where they do not
    /// close (slivers the repair drops: their area vectors' sum `F` moves it by up to
    /// `|F| · d / 6` about points of their box of diagonal `d`), plus `NEEDLE_AREA · d³` for an
    /// empty mesh (tetrahedral shells of needles the needle pass deleted whole). The last guard
    /// against a wrong result: what the command line checks before writing a boolean's or a
    /// scene's result, and [`Solid::to_checked_mesh`] before returning it. Two passes over the
    /// polygons and two over the mesh's triangles: on rocker-arm ∪ moved, 10.7 M instructions,
    /// 0.7 % of the command line's run and a tenth of its [`Solid::to_mesh`].
    ///
    /// ```
    /// use bspcsg::{Error, Solid};
    /// let cube = Solid::cube(1.0)?;
    /// assert!(cube.check_mesh_volume(&cube.to_mesh()).is_ok());
    /// let bigger = Solid::cube(1.1)?.to_mesh();
    /// assert!(matches!(cube.check_mesh_volume(&bigger), Err(Error::WrongVolume { .. })));
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::WrongVolume`] where they differ by more.
    pub fn check_mesh_volume(&self, mesh: &Mesh) -> Result<()> {
        // One pass: the volume as `Solid::volume` sums it (cones to the box centre), the area
        // and the area vectors' sum.
        let bbox = self.bbox();
        let apex = bbox.center();
        let (mut six, mut area, mut flux) = (0.0, 0.0, glam::DVec3::ZERO);
        for p in self.polygons() {
            six += p.signed_volume6(apex);
            let a = p.area();
            area += a.abs();
            flux += a * p.plane().normal;
        }
        let polygons = six / 6.0;
        let got = mesh.volume();
        let open = flux.length() * bbox.diagonal() / 6.0;
        // A tetrahedral shell the needle pass deletes whole holds below `NEEDLE_AREA · d³/3`,
        // `d` its own diagonal, at most the box's: where it was all the mesh had (an
        // intersection of faces touching along a line, one turned a hair), nothing is left
        // for 2 % of the rest to cover it. Only an empty mesh gets this term.
        let tetrahedron = if mesh.is_empty() {
            crate::geom::NEEDLE_AREA * bbox.diagonal().powi(3)
        } else {
            0.0
        };
        let bound = MESH_VOLUME_RELATIVE * polygons.abs().max(got.abs())
            + MESH_VOLUME_TOLERANCES * self.tolerance().eps() * area
            + open
            + tetrahedron;
        // Written so that a NaN anywhere refuses.
        if (got - polygons).abs() <= bound {
            return Ok(());
        }
        Err(Error::WrongVolume {
            mesh: got,
            polygons,
            bound,
        })
    }

    /// [`Solid::to_mesh`], checked: the mesh of a solid within the precision contract that is
    /// a closed 2-manifold (or empty). What the command line writes, and what a caller passing
    /// the result on (to a file, a slicer, another program) can rely on.
    ///
    /// The booleans of solids are meant to give solids; where they do not (a fault of the
    /// kernel on hard input: a feature 10⁻²⁰ of its neighbour's size, a difference of nearly
    /// equal operands), this says so instead of handing over a broken mesh; a caller that
    /// wants the mesh anyway takes [`Solid::to_mesh`].
    ///
    /// ```
    /// use bspcsg::{Error, Solid};
    /// use bspcsg::glam::DVec3;
    /// let a = Solid::cube(1.0)?;
    /// let b = Solid::cube(1.0)?.translate(DVec3::splat(0.5))?;
    /// let mesh = (&a | &b).to_checked_mesh()?;
    /// assert!(mesh.report().is_closed_manifold());
    /// // Taking the mesh even when it is broken:
    /// let mesh = match (&a - &b).to_checked_mesh() {
    ///     Ok(mesh) => mesh,
    ///     Err(Error::BrokenResult { .. }) => (&a - &b).to_mesh(),
    ///     Err(e) => return Err(e),
    /// };
    /// assert!((mesh.volume() - 0.875).abs() < 1e-12);
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::BeyondBudget`] as [`Solid::check_budget`], [`Error::BeyondPrecision`] as
    /// [`Solid::check_precision`], [`Error::BrokenResult`]
    /// with the mesh's [`MeshReport`](crate::MeshReport) as text when the mesh is not empty
    /// and not a closed 2-manifold, and [`Error::WrongVolume`] as
    /// [`Solid::check_mesh_volume`].
    pub fn to_checked_mesh(&self) -> Result<Mesh> {
        self.check_budget()?;
        self.check_precision()?;
        let mesh = self.to_mesh();
        let report = mesh.report();
        if mesh.is_empty() || report.is_closed_manifold() {
            self.check_mesh_volume(&mesh)?;
            return Ok(mesh);
        }
        Err(Error::BrokenResult {
            report: report.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::error::Error;
    use crate::mesh::Mesh;
    use crate::solid::Solid;

    #[test]
    fn a_broken_solid_is_refused_with_its_report_and_mesh() {
        // One face of a cube: open, as no boolean of solids should leave it.
        let cube = Solid::cube(1.0).unwrap();
        let open: Vec<_> = cube.polygons().iter().take(1).cloned().collect();
        let open = Solid::from_polygons(open);
        match open.to_checked_mesh() {
            Err(e @ Error::BrokenResult { .. }) => {
                let Error::BrokenResult { report } = &e else {
                    unreachable!()
                };
                assert_eq!(*report, open.to_mesh().report().to_string());
                assert!(report.contains("NOT a closed 2-manifold"), "{report}");
                assert!(e.to_string().contains("not a closed 2-manifold"), "{e}");
            }
            other => panic!("{other:?}"),
        }
        assert!(
            cube.to_checked_mesh()
                .unwrap()
                .report()
                .is_closed_manifold()
        );
        assert_eq!(Solid::default().to_checked_mesh().unwrap(), Mesh::default());
        // Beyond precision: two unit cubes overlapping by half 10¹² from the origin.
        let far = |x: f64| {
            Solid::cube(1.0)
                .unwrap()
                .translate(DVec3::new(x, 1e12, 0.0))
                .unwrap()
        };
        let both = &far(0.0) | &far(0.5);
        assert!(matches!(
            both.to_checked_mesh(),
            Err(Error::BeyondPrecision { .. })
        ));
    }

    /// Issue 12 (no silent wrong answer): a mesh that bounds another volume than the solid's
    /// polygons (larger, inside out) is refused as [`Error::WrongVolume`]; the solid's own mesh
    /// passes, and so does the empty mesh of polygons that close nothing (a lone sliver face
    /// whose own volume is only that of its cone to the box centre).
    #[test]
    fn a_mesh_bounding_another_volume_than_its_solid_is_refused() {
        let cube = Solid::cube(1.0).unwrap();
        assert!(cube.check_mesh_volume(&cube.to_mesh()).is_ok());
        let larger = Solid::cube(1.1).unwrap().to_mesh();
        let Err(Error::WrongVolume {
            mesh,
            polygons,
            bound,
        }) = cube.check_mesh_volume(&larger)
        else {
            panic!("a larger cube passed");
        };
        assert!((mesh - 1.331).abs() < 1e-12 && (polygons - 1.0).abs() < 1e-12);
        // 2e-2 of 1.331, plus 128 tolerances (1e-12 of the diagonal) times the area 6.
        assert!((bound - (2e-2 * 1.331 + 128.0 * 1e-12 * 3f64.sqrt() * 6.0)).abs() < 1e-9);
        let mut inside_out = cube.to_mesh();
        for t in &mut inside_out.triangles {
            t.swap(1, 2);
        }
        assert!(matches!(
            cube.check_mesh_volume(&inside_out),
            Err(Error::WrongVolume { .. })
        ));
        assert!(cube.check_mesh_volume(&Mesh::default()).is_err());
        // Two faces of a cube meeting at an edge, alone: their volume is their cones' to the
        // box centre (1/3); no closed mesh bounds any, and their area vectors' sum says how
        // unsure that figure is (|F| d / 6 = 0.408).
        let faces: Vec<_> = cube
            .polygons()
            .iter()
            .filter(|p| p.plane().normal.z > 0.5 || p.plane().normal.x > 0.5)
            .cloned()
            .collect();
        let face = Solid::from_polygons(faces);
        assert!(
            (face.volume() - 1.0 / 3.0).abs() < 1e-12,
            "{}",
            face.volume()
        );
        assert!(face.check_mesh_volume(&Mesh::default()).is_ok());
    }
}
