//! Mesh errors: components that cannot be found or read, and meshes too
//! large to build. Input: a component symbol or file; output: a diagnostic
//! naming the symbol, its span, and every place searched.

use miette::{Diagnostic, NamedSource, SourceSpan};
use thiserror::Error;

#[derive(Debug, Error, Diagnostic)]
pub enum MeshError {
    #[error(transparent)]
    #[diagnostic(transparent)]
    MissingComponent(Box<MissingComponent>),

    #[error(transparent)]
    #[diagnostic(transparent)]
    Distorted(Box<Distorted>),

    #[error(transparent)]
    #[diagnostic(transparent)]
    WideLines(Box<WideLines>),

    #[error("cpfg surface `~{name}` cannot be drawn: {why}")]
    #[diagnostic(
        code(lsys::mesh::cpfg_surface),
        severity(Warning),
        help("`build` and `render` draw nothing for `~{name}`, as cpfg does; fix the surface file or its `surface:` line")
    )]
    CpfgSurface { name: String, why: String },

    #[error("component `~{name}`: {path} leads outside {dir}")]
    #[diagnostic(
        code(lsys::mesh::component_outside),
        help("a component file must resolve (links followed) inside the folder it is found in; copy the file there instead of linking to it")
    )]
    ComponentOutside {
        name: String,
        path: String,
        dir: String,
    },

    #[error("cannot read component `~{name}` from {path}: {cause}")]
    #[diagnostic(
        code(lsys::mesh::component_io),
        help("check that the file is readable")
    )]
    ComponentIo {
        name: String,
        path: String,
        cause: std::io::Error,
    },

    #[error("component `~{name}` in {path} is not a usable OBJ model: {reason}")]
    #[diagnostic(
        code(lsys::mesh::bad_component),
        help("open the file in a modelling program and export it again as a triangulated Wavefront OBJ with faces (`f` lines) whose indices point at existing vertices")
    )]
    BadComponent {
        name: String,
        path: String,
        reason: String,
    },

    #[error("component `~{name}` is the grammar {origin}, which does not build")]
    #[diagnostic(
        code(lsys::mesh::component_grammar),
        help("{details}\nfix the grammar (`lsys check {origin}`), or put an OBJ model `{name}.obj` in a components directory instead")
    )]
    ComponentGrammar {
        name: String,
        origin: String,
        details: String,
    },

    #[error("the model would have more than {limit} triangles (reached {reached})")]
    #[diagnostic(
        code(lsys::mesh::too_many_triangles),
        help("derive fewer steps, or raise the limit with `--max-triangles N`")
    )]
    TooManyTriangles { limit: usize, reached: usize },
}

/// A placed component that is nowhere to be found.
#[derive(Debug, Error, Diagnostic)]
#[error("component `~{name}` not found")]
#[diagnostic(
    code(lsys::mesh::missing_component),
    help("looked in:\n{searched}\nput `{name}.obj` in one of these places, pass `--components DIR`, or use a built-in component ({builtin})")
)]
pub struct MissingComponent {
    pub name: String,
    pub searched: String,
    pub builtin: String,
    #[source_code]
    pub src: NamedSource<crate::source::SourceText>,
    #[label("placed here")]
    pub span: Option<SourceSpan>,
}

/// A warning: `~X` or `~X(s)` draws an elongated model as a cube
/// (`super::distortion`).
#[derive(Debug, Error, Diagnostic)]
#[error("`~{name}` is modelled {modelled} but drawn as a cube of side {side}: {factor} times out of proportion")]
#[diagnostic(
    code(lsys::mesh::distorted_component),
    severity(Warning),
    help("every model is fitted to the unit box one axis at a time, so `~{name}` and `~{name}(s)` ({count} {placements}) draw a cube; to keep its proportions give three scales, width, height and depth: `{example}`; if the cube is meant, write `~{name}(s, s, s)`")
)]
pub struct Distorted {
    pub name: String,
    pub modelled: String,
    pub side: String,
    pub factor: String,
    pub count: usize,
    pub placements: &'static str,
    pub example: String,
    #[source_code]
    pub src: NamedSource<crate::source::SourceText>,
    #[label("placed with one scale")]
    pub span: Option<SourceSpan>,
}

/// A warning: line widths that dwarf the model (`super::widths`).
#[derive(Debug, Error, Diagnostic)]
#[error("the lines are up to {widest} wide (typically {typical}) in a model {size} across: the tubes hide its shape")]
#[diagnostic(
    code(lsys::mesh::wide_lines),
    severity(Warning),
    help("widths are in the model's units, like steps, and the widest line here is {ratio} times the model's size; ABOP and cpfg give widths in pixels (`!(10)`). Scale the widths down (`!(w*0.01)`) or the steps up; a cpfg `.l` file is read with cpfg's pixel widths (docs/cpfg.md)")
)]
pub struct WideLines {
    pub widest: String,
    pub typical: String,
    pub size: String,
    pub ratio: String,
    #[source_code]
    pub src: NamedSource<crate::source::SourceText>,
    #[label("widths set here")]
    pub span: Option<SourceSpan>,
}
