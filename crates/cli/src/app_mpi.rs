//! `mpirun -n N bipo run scene.toml` (issue 41): the same scene file, the bulk's `K x = b`
//! solved by PETSc under MPI when the scene says `[analysis] linear_solver = "petsc"` (and `bipo`
//! is built with the feature `petsc`).
//!
//! Every rank builds the whole study as `bipo run` does (mesh, model, zones) and runs the same
//! contact steps; only the model's solves go to the distributed structure
//! (`bipotential_petsc::PetscStructure`, through `ElasticModel::set_reduced_solver`), which
//! takes rank 0's right-hand sides and returns the same solution to every rank — so the
//! interface (candidates, `F*`, the local solve) is rank 0's, and the answer is the serial one
//! to the solver's tolerance. Outputs are written once: rank 0 writes the CSV files,
//! `summary.json`, the plots and the interface series into the output directory; the mesh
//! series is ParaView's parallel format (each rank's piece, `mesh_NNNN.pvtu`, `mesh.pvd`:
//! `run::Pieces`); the other ranks write their other files in a scratch directory they remove.
//!
//! Every rank holds the assembled `K` (the model is built without a factorisation:
//! `ElasticModel::unfactored`) and its share of PETSc's distributed matrix and solver; the
//! interface's data (`F*`, the local problem) are whole on every rank.
//!
//! 2D scenes (plane strain, plane stress, axisymmetry) and 3D ones are served. Refused, naming
//! the key: a scene that asks for PETSc in a `bipo` built without it; a run under `mpirun`
//! with more than one rank of a scene that does not ask for it (every rank would solve the
//! whole model and write the same files); on the distributed path, a preset (`preset`), a
//! dynamic scene (`analysis.dynamic`), a plastic material (`materials`), ties (`ties`) and a
//! body that only contact holds (`analysis.floating`).
//!
//! Errors: a scene error is found alike by every rank before MPI starts and printed by rank 0
//! only; a failure during the run ends every rank (`MPI_Abort`) with its message, rank 0's
//! when it fails too (the other ranks wait a moment before aborting, so that the same error
//! is not printed N times), never a hang.

use crate::build;
use crate::error::{CliError, CliResult, KeyPath};
use crate::raw::{LinearSolverSpec, PetscSpec};
use crate::run::Summary;
use std::path::Path;

/// How `bipo run` prints a study's header (`"run"`, the scene, the study) and its summary (the
/// command's, handed over).
pub(crate) type Prints<const D: usize> = (
    fn(&str, &build::Loaded, &build::Study<D>),
    fn(&Summary<D>, &Path),
);

/// [`launch`]'s number of ranks; the ranks other than 0 print nothing from now on (rank 0
/// prints each line and each scene error once; a failure during a distributed run ends every
/// rank with its message).
pub(crate) fn launch_quietly() -> usize {
    let (rank, size) = launch();
    if rank > 0 {
        crate::out::silence();
    }
    size
}

/// This process's rank and the number of ranks as the MPI launcher sets them in the
/// environment (Open MPI's `OMPI_COMM_WORLD_RANK` / `_SIZE`, MPICH's `PMI_RANK` / `PMI_SIZE`),
/// read before MPI is initialised: `(0, 1)` outside a launcher.
pub(crate) fn launch() -> (usize, usize) {
    let var = |names: [&str; 2]| {
        names
            .iter()
            .find_map(|n| std::env::var(n).ok()?.trim().parse::<usize>().ok())
    };
    let size = var(["OMPI_COMM_WORLD_SIZE", "PMI_SIZE"])
        .unwrap_or(1)
        .max(1);
    let rank = var(["OMPI_COMM_WORLD_RANK", "PMI_RANK"]).unwrap_or(0);
    (rank.min(size - 1), size)
}

/// PETSc's settings when the scene asks for it, checked as [`linear_solver`] does.
///
/// # Errors
/// As [`linear_solver`].
pub(crate) fn petsc_spec(loaded: &build::Loaded, size: usize) -> CliResult<Option<PetscSpec>> {
    Ok(match linear_solver(loaded, size)? {
        LinearSolverSpec::Petsc(spec) => Some(spec),
        LinearSolverSpec::Direct => None,
    })
}

/// The linear solver the scene asks for, checked against how `bipo` was built and launched
/// (`size` ranks).
///
/// # Errors
/// At `analysis.linear_solver`: PETSc asked for in a `bipo` without the feature; several ranks
/// for a scene that does not ask for PETSc.
pub(crate) fn linear_solver(loaded: &build::Loaded, size: usize) -> CliResult<LinearSolverSpec> {
    let p = KeyPath::root().key("analysis");
    let spec = match &loaded.scene.analysis {
        Some(a) => a.linear_solver(&p)?,
        None => LinearSolverSpec::Direct,
    };
    let key = KeyPath::root().key("analysis").key("linear_solver");
    match spec {
        LinearSolverSpec::Direct if size > 1 => Err(CliError::at(
            &key,
            format!(
                "`{key}`: bipo runs under MPI on {size} ranks, but the scene solves in one \
                 process (each rank would run the whole scene): set `{key}` = \"petsc\", or run \
                 without mpirun"
            ),
        )),
        LinearSolverSpec::Petsc(_) if !cfg!(feature = "petsc") => Err(CliError::at(
            &key,
            format!(
                "`{key}` = \"petsc\": this bipo is built without PETSc; build it with the \
                 feature `petsc` (`cargo install --path crates/cli --features petsc`, with the \
                 packages libpetsc-real-dev and libopenmpi-dev)"
            ),
        )),
        spec => Ok(spec),
    }
}

/// The refusal of a built study the distributed path does not serve (a dynamic or plastic
/// one), naming the key that makes it what it is (a static elastic one is served: `bipo run`
/// does not ask).
pub(crate) fn refuse(built: &build::Built) -> CliError {
    match built {
        build::Built::PlaneDynamic(_) | build::Built::SolidDynamic(_) => unsupported(
            KeyPath::root().key("analysis").key("dynamic"),
            "a dynamic scene",
        ),
        build::Built::PlanePlastic(_) | build::Built::SolidPlastic(_) => {
            unsupported(KeyPath::root().key("materials"), "a plastic material")
        }
        build::Built::Plane(_) | build::Built::Solid(_) => {
            CliError::failed("a served study reached the refusal (internal routing error)")
        }
    }
}

/// The refusal of a scene kind the distributed path does not serve, at `key`.
pub(crate) fn unsupported(key: KeyPath, what: &str) -> CliError {
    CliError::at(
        &key,
        format!(
            "`{key}`: {what} is not run distributed yet (`analysis.linear_solver` = \"petsc\" \
             serves static scenes with elastic materials, key by key, held by supports); remove `analysis.linear_solver` to \
             run it in one process"
        ),
    )
}

#[cfg(feature = "petsc")]
pub(crate) use with_petsc::run_study;

/// Without the feature `petsc` no scene gets here ([`linear_solver`] refuses it first).
#[cfg(not(feature = "petsc"))]
pub(crate) fn run_study<const D: usize>(
    _: build::Study<D>,
    _: &build::Loaded,
    _: (Option<std::path::PathBuf>, bool),
    _: PetscSpec,
    _: Prints<D>,
) -> CliResult<()>
where
    fem_core::Dim<D>: crate::run::Drive<D>,
{
    Err(CliError::failed(
        "this bipo is built without the feature `petsc`",
    ))
}

#[cfg(feature = "petsc")]
mod with_petsc {
    use super::{Prints, unsupported};
    use crate::build::{self, Body, Study};
    use crate::error::{CliError, CliResult, KeyPath};
    use crate::raw::PetscSpec;
    use crate::run::{self, Drive, Pieces};
    use bipotential_petsc::{LinearSolver, Petsc, PetscStructure};
    use fem_core::faer::MatMut;
    use fem_core::model::ReducedSolver;
    use fem_core::{Dim, ElasticModel, FemError, Material, Structure};
    use std::collections::BTreeMap;
    use std::path::PathBuf;
    use std::sync::Arc;

    /// The distributed structure as the model's solver of `K x = b`.
    struct PetscSolve<const D: usize>(PetscStructure<'static, D>)
    where
        Dim<D>: Drive<D>;

    // SAFETY: bipo calls the model's solves from its main thread only (the contact steps are
    // sequential around them; faer's threads work inside factorisations and dense kernels, never
    // through the model), so the PETSc objects are never touched from two threads.
    unsafe impl<const D: usize> Send for PetscSolve<D> where Dim<D>: Drive<D> {}
    // SAFETY: as for `Send`: no two threads ever hold the model at once.
    unsafe impl<const D: usize> Sync for PetscSolve<D> where Dim<D>: Drive<D> {}

    impl<const D: usize> ReducedSolver for PetscSolve<D>
    where
        Dim<D>: Drive<D>,
    {
        /// PETSc's failure, with the scene's keys that change the solver.
        fn solve_many_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), FemError> {
            self.0.solve_many_in_place(rhs).map_err(|e| match e {
                FemError::LinearAlgebra { detail } => FemError::LinearAlgebra {
                    detail: format!(
                        "{detail}; in the scene: `analysis.petsc.max_iterations`, `rtol`, or \
                         `method` = \"mumps\""
                    ),
                },
                e => e,
            })
        }
    }

    /// The method of `[analysis.petsc]` as PETSc's.
    fn method(spec: PetscSpec) -> LinearSolver {
        match spec {
            PetscSpec::CgGamg {
                rtol,
                max_iterations,
            } => LinearSolver::CgGamg {
                rtol,
                max_iterations,
            },
            PetscSpec::Mumps => LinearSolver::Mumps,
        }
    }

    /// `bipo run` of a study on every rank, the solves by PETSc (see the module docs).
    pub(crate) fn run_study<const D: usize>(
        mut study: Study<D>,
        loaded: &build::Loaded,
        (out, quiet): (Option<PathBuf>, bool),
        spec: PetscSpec,
        (print_header, print_summary): Prints<D>,
    ) -> CliResult<()>
    where
        Dim<D>: Drive<D>,
    {
        if !study.model().supports().ties().is_empty() {
            return Err(unsupported(
                KeyPath::root().key("ties"),
                "a scene with ties",
            ));
        }
        if matches!(study.body, Body::Preset(_)) {
            return Err(unsupported(KeyPath::root().key("preset"), "a preset"));
        }
        // shared with the structure, which the study's model holds: PETSc is finalised when
        // the last of the two goes, after the structure's objects
        let petsc = Arc::new(
            Petsc::init().map_err(|e| CliError::failed(format!("PETSc did not start: {e}")))?,
        );
        let (rank, size) = (petsc.rank(), petsc.size());
        let dir =
            run::RunOptions::new(out, study.output.dir.as_deref(), &loaded.path, quiet).out_dir;
        let scratch = std::env::temp_dir().join(format!("bipo-rank{rank}-{}", std::process::id()));
        petsc.or_abort(|| -> Result<CliResult<()>, String> {
            let result = (|| -> CliResult<()> {
                let structure = structure(&petsc, study.model(), spec)?;
                let element_rank = structure.partition().element_rank.clone();
                model_mut(&mut study)?
                    .set_reduced_solver(Box::new(PetscSolve(structure)))
                    .map_err(|e| match e {
                        FemError::Unsupported { .. } => unsupported(
                            KeyPath::root().key("analysis").key("floating"),
                            "a body that only contact holds",
                        ),
                        e => CliError::failed(format!("the PETSc solver: {e}")),
                    })?;
                let mut opts = run::RunOptions::new(
                    Some(if rank == 0 {
                        dir.clone()
                    } else {
                        scratch.clone()
                    }),
                    None,
                    &loaded.path,
                    quiet || rank > 0,
                );
                opts.pieces = Some(Pieces::new(rank, size, &element_rank, dir.clone()));
                print_header("run", loaded, &study);
                crate::out::outln!("distributed: PETSc on {size} rank(s), {spec:?}");
                let summary = run::run(study, &opts)?;
                print_summary(&summary, &opts.out_dir);
                Ok(())
            })();
            if rank > 0 {
                let _ = std::fs::remove_dir_all(&scratch);
            }
            match result {
                Err(e) if size > 1 => {
                    if rank > 0 {
                        // rank 0 most likely failed alike: let its abort print the message
                        std::thread::sleep(std::time::Duration::from_secs(2));
                    }
                    petsc.abort(&e.render(Some(&loaded.source)))
                }
                result => Ok(result),
            }
        })
    }

    /// The distributed structure of `model`'s mesh, setting, materials and supports (its
    /// free-dof numbering is the model's), sharing `petsc`.
    fn structure<const D: usize>(
        petsc: &Arc<Petsc>,
        model: &ElasticModel<D>,
        spec: PetscSpec,
    ) -> CliResult<PetscStructure<'static, D>>
    where
        Dim<D>: Drive<D>,
    {
        let mesh = model.mesh();
        let mut materials: BTreeMap<u32, Material> = BTreeMap::new();
        for e in 0..mesh.element_count() {
            materials
                .entry(mesh.regions()[e])
                .or_insert(*model.material(e));
        }
        let materials: Vec<(u32, Material)> = materials.into_iter().collect();
        PetscStructure::with_setting(
            Arc::clone(petsc),
            mesh.clone(),
            *model.setting(),
            &materials,
            model.supports().clone(),
            method(spec),
        )
        .map_err(|e| CliError::failed(format!("the PETSc structure: {e}")))
    }

    /// The model inside the study's simulation (a scene's key by key: a preset is refused
    /// before).
    fn model_mut<const D: usize>(study: &mut Study<D>) -> CliResult<&mut ElasticModel<D>>
    where
        Dim<D>: Drive<D>,
    {
        match &mut study.body {
            Body::Custom(c) => Ok(c.sim.structure_mut()),
            Body::Preset(_) => Err(unsupported(KeyPath::root().key("preset"), "a preset")),
        }
    }
}
