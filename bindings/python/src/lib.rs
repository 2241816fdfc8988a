//! The `rotlang` Python module: check, expand, explain and format templates.
//!
//! Spans reach Python as code-point offsets (`start`, `end`: what `text[start:end]`
//! slices) and as UTF-8 byte offsets (`byte_start`, `byte_end`). Bad input raises
//! `rotlang.TemplateError` (carrying the diagnostics) or `ValueError`, never crashes.

use pyo3::exceptions::{PyException, PyOverflowError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

use rotlang_core::api::{self, ApiError, ErrorKind, ModelSpec, Style};
use rotlang_core::eval::limits::{self, Given};
use rotlang_core::eval::{self, Model as RustModel, Options};
use rotlang_core::{Diagnostic as RustDiagnostic, Target};

mod dialect;
mod evaluated;

use evaluated::{Evaluated, Finding};

pyo3::create_exception!(
    rotlang,
    TemplateError,
    PyException,
    "The template has errors; `.diagnostics` lists them (`args[1]` too)."
);

pyo3::create_exception!(
    rotlang,
    OptionsError,
    PyValueError,
    "A target, dialect, base or seed that rotlang cannot take (a `ValueError`)."
);

pyo3::create_exception!(
    rotlang,
    ModelError,
    PyValueError,
    "A model that rotlang cannot take: no layers, a bad height or count (a `ValueError`)."
);

pyo3::create_exception!(
    rotlang,
    ProfileError,
    PyValueError,
    "A profile file that cannot be read at all (a `ValueError`)."
);

/// A refusal of the shared API (`rotlang::api`, which the C and JavaScript bindings
/// check their input with too): the same message in every language.
fn refused(e: ApiError) -> PyErr {
    match e.kind {
        ErrorKind::Options => OptionsError::new_err(e.message),
        ErrorKind::Model => ModelError::new_err(e.message),
        ErrorKind::Profile => ProfileError::new_err(e.message),
    }
}

/// One diagnostic of a template.
#[pyclass(frozen, get_all, skip_from_py_object, module = "rotlang")]
#[derive(Clone)]
struct Diagnostic {
    /// Stable code, e.g. `rotlang_core::unknown-sign`.
    code: String,
    /// `"error"` or `"warning"`.
    severity: String,
    message: String,
    help: Option<String>,
    /// Code-point offsets of the primary span: `text[start:end]`.
    start: usize,
    end: usize,
    /// UTF-8 byte offsets of the same span.
    byte_start: usize,
    byte_end: usize,
}

#[pymethods]
impl Diagnostic {
    fn __repr__(&self) -> String {
        format!(
            "Diagnostic({}, {:?}, {:?}, start={}, end={})",
            self.severity, self.code, self.message, self.start, self.end
        )
    }
}

fn diagnostic(text: &str, d: &RustDiagnostic) -> Diagnostic {
    let span = d.primary_span();
    let chars = |byte: usize| {
        let byte = rotlang_core::diagnostic::floor_char_boundary(text, byte);
        text[..byte].chars().count()
    };
    Diagnostic {
        code: d.code.to_string(),
        severity: d.severity.as_str().to_string(),
        message: d.message.clone(),
        help: d.help.clone(),
        start: chars(span.start),
        end: chars(span.end),
        byte_start: span.start,
        byte_end: span.end,
    }
}

fn target(name: &str) -> PyResult<Target> {
    api::target(name).map_err(refused)
}

/// The TemplateError for a template with errors.
fn template_error(py: Python<'_>, text: &str, diagnostics: &[RustDiagnostic]) -> PyErr {
    let list: Vec<Diagnostic> = diagnostics.iter().map(|d| diagnostic(text, d)).collect();
    let first = diagnostics
        .iter()
        .find(|d| d.is_error())
        .map_or(String::new(), |d| format!("{}: {}", d.code, d.message));
    let errors = diagnostics.iter().filter(|d| d.is_error()).count();
    let message = format!("the template has {errors} error(s); first: {first}");
    match PyList::new(py, list) {
        Ok(list) => {
            let err = TemplateError::new_err((message, list.clone().unbind()));
            let _ = err.value(py).setattr("diagnostics", list);
            err
        }
        Err(e) => e,
    }
}

/// An integer argument as Python gave it, checked against its range by
/// `rotlang::api` (the C and JavaScript bindings' ranges and messages): a negative or
/// too large number raises `ValueError` with the range, not PyO3's `OverflowError`.
#[derive(Clone, Debug)]
enum Int {
    Given(i128),
    /// Beyond 128 bits: its repr, for the message.
    Huge(String),
}

impl<'a, 'py> FromPyObject<'a, 'py> for Int {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Int> {
        match obj.extract::<i128>() {
            Ok(v) => Ok(Int::Given(v)),
            Err(e) if e.is_instance_of::<PyOverflowError>(obj.py()) => {
                Ok(Int::Huge(obj.repr()?.to_string()))
            }
            Err(e) => Err(e),
        }
    }
}

impl Int {
    const ZERO: Int = Int::Given(0);

    /// The number for the shared API, or its refusal for one beyond 128 bits (`name` in
    /// snake case).
    fn given(&self, name: &'static str) -> PyResult<Given> {
        match self {
            Int::Given(v) => Ok(Given::Int(*v)),
            Int::Huge(shown) => Err(refused(api::out_of_range(name, Style::Snake, shown))),
        }
    }
}

/// A model from its description, checked by the shared API.
fn model(spec: ModelSpec<'_>, bottom: &Int, top: &Int) -> PyResult<Model> {
    let spec = ModelSpec {
        bottom_shells: Some(bottom.given("bottom_shells")?),
        top_shells: Some(top.given("top_shells")?),
        ..spec
    };
    let inner = spec.build(Style::Snake).map_err(refused)?;
    Ok(Model { inner })
}

/// The layers of one object: a list of heights or a uniform model, with `h`, `B`, `T`.
#[pyclass(frozen, skip_from_py_object, module = "rotlang")]
#[derive(Clone)]
struct Model {
    inner: RustModel,
}

#[pymethods]
impl Model {
    /// `layers` layers of `layer_height` mm, the first of `first_layer_height`.
    #[staticmethod]
    #[pyo3(signature = (layers, layer_height=0.2, first_layer_height=None, bottom_shells=Int::Given(3), top_shells=Int::Given(4)))]
    fn uniform(
        layers: Int,
        layer_height: f64,
        first_layer_height: Option<f64>,
        bottom_shells: Int,
        top_shells: Int,
    ) -> PyResult<Model> {
        let spec = ModelSpec {
            layers: Some(layers.given("layers")?),
            layer_height: Some(layer_height),
            first_layer_height,
            ..ModelSpec::default()
        };
        model(spec, &bottom_shells, &top_shells)
    }

    /// A model from every layer's height (mm, bottom to top) and the standard height.
    #[staticmethod]
    #[pyo3(signature = (heights, layer_height, bottom_shells=Int::Given(3), top_shells=Int::Given(4)))]
    fn from_heights(
        heights: Vec<f64>,
        layer_height: f64,
        bottom_shells: Int,
        top_shells: Int,
    ) -> PyResult<Model> {
        let spec = ModelSpec {
            // Moved into the model: the list is not copied again.
            heights: Some(heights.into()),
            layer_height: Some(layer_height),
            ..ModelSpec::default()
        };
        model(spec, &bottom_shells, &top_shells)
    }

    /// An object `height` mm tall in layers of `layer_height`.
    #[staticmethod]
    #[pyo3(signature = (height, layer_height=0.2, first_layer_height=None, bottom_shells=Int::Given(3), top_shells=Int::Given(4)))]
    fn from_total_height(
        height: f64,
        layer_height: f64,
        first_layer_height: Option<f64>,
        bottom_shells: Int,
        top_shells: Int,
    ) -> PyResult<Model> {
        let spec = ModelSpec {
            height: Some(height),
            layer_height: Some(layer_height),
            first_layer_height,
            ..ModelSpec::default()
        };
        model(spec, &bottom_shells, &top_shells)
    }

    /// The documentation's 20 mm cube: 100 layers of 0.2 mm, 3 bottom and 4 top shells.
    #[staticmethod]
    fn cube20() -> Model {
        Model {
            inner: RustModel::cube20(),
        }
    }

    fn __len__(&self) -> usize {
        self.inner.len()
    }

    #[getter]
    fn layer_height(&self) -> f64 {
        self.inner.layer_height()
    }

    #[getter]
    fn bottom_shells(&self) -> u32 {
        self.inner.bottom_shells()
    }

    #[getter]
    fn top_shells(&self) -> u32 {
        self.inner.top_shells()
    }

    /// The object height in mm.
    #[getter]
    fn height(&self) -> f64 {
        self.inner.object_height()
    }

    fn __repr__(&self) -> String {
        format!(
            "Model(layers={}, layer_height={}, height={}, bottom_shells={}, top_shells={})",
            self.inner.len(),
            rotlang_core::number::height(self.inner.layer_height()),
            rotlang_core::number::height(self.inner.object_height()),
            self.inner.bottom_shells(),
            self.inner.top_shells()
        )
    }
}

/// Every layer's angle, fill and the dialect's findings.
#[pyclass(frozen, get_all, skip_from_py_object, module = "rotlang")]
struct Expansion {
    /// Degrees, base included, not wrapped.
    angles: Py<PyAny>,
    /// `"sparse"`, `"dense"`, `"solid"`, `"concentric"`, `"monotonic"`, `"rectilinear"`.
    fills: Vec<&'static str>,
    findings: Vec<Finding>,
}

fn evaluate(
    py: Python<'_>,
    text: &str,
    model: Option<&Model>,
    options: Options,
    target_name: &str,
    dialect_name: &str,
    want_fills: bool,
) -> PyResult<Evaluated> {
    let target = target(target_name)?;
    let dialect = dialect::Dialect::from_name(dialect_name).map_err(refused)?;
    let cube;
    let model = match model {
        Some(m) => &m.inner,
        None => {
            cube = RustModel::cube20();
            &cube
        }
    };
    match dialect {
        dialect::Dialect::Rotlang => {
            let parse = rotlang_core::parse(text, target);
            if parse.has_errors() {
                return Err(template_error(py, text, &parse.diagnostics));
            }
            // The evaluation holds no Python object: other Python threads may run.
            Ok(py.detach(|| {
                let mut angles = Vec::with_capacity(model.len());
                let mut fills = Vec::new();
                for layer in eval::layers(&parse.template, model, options) {
                    angles.push(layer.angle);
                    if want_fills {
                        fills.push(layer.fill.name());
                    }
                }
                Evaluated {
                    angles,
                    fills,
                    findings: Vec::new(),
                }
            }))
        }
        other => dialect::evaluate(py, other, text, model, options, want_fills),
    }
}

/// A Python `array('d')` holding `values` (NumPy-free, one copy of 8 bytes per value).
fn float_array<'py>(py: Python<'py>, values: &[f64]) -> PyResult<Bound<'py, PyAny>> {
    let array = py.import("array")?.getattr("array")?.call1(("d",))?;
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_ne_bytes()).collect();
    array.call_method1("frombytes", (PyBytes::new(py, &bytes),))?;
    Ok(array)
}

fn angles_object<'py>(py: Python<'py>, angles: &[f64], array: bool) -> PyResult<Bound<'py, PyAny>> {
    if array {
        float_array(py, angles)
    } else {
        Ok(PyList::new(py, angles)?.into_any())
    }
}

/// The angle (degrees) of every layer of `model` (default: the 20 mm cube) under the
/// template: a `list` of floats, or an `array('d')` with `array=True`.
#[pyfunction]
#[pyo3(signature = (template, model=None, *, base=0.0, seed=Int::ZERO, target="sparse", dialect="rotlang", array=false))]
#[allow(clippy::too_many_arguments)] // Python keyword arguments
fn expand<'py>(
    py: Python<'py>,
    template: &str,
    model: Option<&Model>,
    base: f64,
    seed: Int,
    target: &str,
    dialect: &str,
    array: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let options = options(base, &seed)?;
    let done = evaluate(py, template, model, options, target, dialect, false)?;
    angles_object(py, &done.angles, array)
}

/// Angles, fills and findings together (see `Expansion`).
#[pyfunction]
#[pyo3(signature = (template, model=None, *, base=0.0, seed=Int::ZERO, target="sparse", dialect="rotlang", array=false))]
#[allow(clippy::too_many_arguments)] // Python keyword arguments
fn evaluate_layers(
    py: Python<'_>,
    template: &str,
    model: Option<&Model>,
    base: f64,
    seed: Int,
    target: &str,
    dialect: &str,
    array: bool,
) -> PyResult<Expansion> {
    let options = options(base, &seed)?;
    let done = evaluate(py, template, model, options, target, dialect, true)?;
    Ok(Expansion {
        angles: angles_object(py, &done.angles, array)?.unbind(),
        fills: done.fills,
        findings: done.findings,
    })
}

/// The base and seed, in the ranges every binding takes (`rotlang::api`).
fn options(base: f64, seed: &Int) -> PyResult<Options> {
    api::options(Some(base), Some(seed.given("seed")?), limits::MAX_SEED).map_err(refused)
}

/// Every diagnostic (errors and warnings) of a template; an empty list when it is clean.
#[pyfunction]
#[pyo3(signature = (template, target="sparse"))]
fn check(template: &str, target: &str) -> PyResult<Vec<Diagnostic>> {
    // The diagnostics without the IR: a megabyte template costs what `rotlang check` does
    // (the IR was 40-130x the text, issue 22).
    let parse = rotlang_core::check(template, self::target(target)?);
    Ok(parse
        .diagnostics
        .iter()
        .map(|d| diagnostic(template, d))
        .collect())
}

/// The canonical form of a template (`, ` between instructions). Raises TemplateError
/// when it has errors.
#[pyfunction]
#[pyo3(signature = (template, target="sparse"))]
fn format(py: Python<'_>, template: &str, target: &str) -> PyResult<String> {
    let target = self::target(target)?;
    match rotlang_core::format::format(template, target) {
        Some(text) => Ok(text),
        None => Err(template_error(
            py,
            template,
            &rotlang_core::parse(template, target).diagnostics,
        )),
    }
}

/// The template in plain words, each instruction with its layer range on `model`.
#[pyfunction]
#[pyo3(signature = (template, model=None, target="sparse"))]
fn explain(
    py: Python<'_>,
    template: &str,
    model: Option<&Model>,
    target: &str,
) -> PyResult<String> {
    let target = self::target(target)?;
    Ok(dialect::explain(
        py,
        template,
        target,
        model.map(|m| &m.inner),
    ))
}

/// The documentation of a diagnostic code (`"rotlang::unknown-sign"` or `"unknown-sign"`):
/// a dict with `code`, `severity`, `summary`, `explanation`, `example`, `fix`; `None`
/// for a code rotlang does not have.
#[pyfunction]
fn explain_code<'py>(py: Python<'py>, code: &str) -> PyResult<Option<Bound<'py, PyDict>>> {
    let Some(doc) = rotlang_core::explain::code(code) else {
        return Ok(None);
    };
    let dict = PyDict::new(py);
    dict.set_item("code", doc.code)?;
    dict.set_item("severity", doc.severity)?;
    dict.set_item("summary", doc.summary)?;
    dict.set_item("explanation", doc.explanation)?;
    dict.set_item("example", doc.example)?;
    dict.set_item("fix", doc.fix)?;
    Ok(Some(dict))
}

/// The templates, model and direction of a profile file, read by `rotlang_profile::api::profile`
/// (what the JavaScript binding's `readProfile` shows): `name` picks the kind by its
/// extension (`.json`/`.jsonc` presets, `.ini` exports, `.rot` templates); `content` is
/// its text or bytes. A dict: `kind`, `templates` (dicts with `key`, `object`, `target`,
/// `text` and `base`, the direction the tools add to that template), `model` (a `Model`),
/// `first_layer_height`, `base`, `notes` (dicts with `message` and `error`) and
/// `has_errors`. Raises `ProfileError` for a file that cannot be read at all.
#[pyfunction]
fn read_profile<'py>(
    py: Python<'py>,
    name: &str,
    content: Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let bytes: Vec<u8> = match content.extract::<String>() {
        Ok(text) => text.into_bytes(),
        Err(_) => content.extract::<Vec<u8>>()?,
    };
    let p = py
        .detach(|| rotlang_profile::api::profile(name, &bytes))
        .map_err(refused)?;
    let templates = PyList::empty(py);
    for t in &p.templates {
        let d = PyDict::new(py);
        d.set_item("key", &t.key)?;
        d.set_item("object", &t.object)?;
        d.set_item(
            "target",
            api::TARGETS[usize::from(t.target == Target::Solid)],
        )?;
        d.set_item("text", &t.text)?;
        d.set_item("base", t.base)?;
        templates.append(d)?;
    }
    let notes = PyList::empty(py);
    for n in &p.notes {
        let d = PyDict::new(py);
        d.set_item("message", &n.message)?;
        d.set_item("error", n.error)?;
        notes.append(d)?;
    }
    let dict = PyDict::new(py);
    dict.set_item("kind", p.kind)?;
    dict.set_item("templates", templates)?;
    dict.set_item("model", Model { inner: p.model })?;
    dict.set_item("first_layer_height", p.first_layer_height)?;
    dict.set_item("base", p.base)?;
    dict.set_item("notes", notes)?;
    dict.set_item("has_errors", p.has_errors)?;
    Ok(dict)
}

/// Wraps an angle into `[0, 360)` and prints it without float noise (`"30"`, `"22.5"`).
#[pyfunction]
fn format_angle(degrees: f64) -> String {
    let wrapped = rotlang_core::number::wrap(degrees, rotlang_core::number::Wrap::Turn);
    rotlang_core::number::angle(wrapped).to_string()
}

#[pymodule]
fn rotlang(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("TemplateError", m.py().get_type::<TemplateError>())?;
    m.add("OptionsError", m.py().get_type::<OptionsError>())?;
    m.add("ModelError", m.py().get_type::<ModelError>())?;
    m.add("ProfileError", m.py().get_type::<ProfileError>())?;
    m.add("DIALECTS", dialect::NAMES.to_vec())?;
    m.add_class::<Diagnostic>()?;
    m.add_class::<Model>()?;
    m.add_class::<Finding>()?;
    m.add_class::<Expansion>()?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(expand, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_layers, m)?)?;
    m.add_function(wrap_pyfunction!(format, m)?)?;
    m.add_function(wrap_pyfunction!(format_angle, m)?)?;
    m.add_function(wrap_pyfunction!(explain, m)?)?;
    m.add_function(wrap_pyfunction!(explain_code, m)?)?;
    m.add_function(wrap_pyfunction!(read_profile, m)?)?;
    Ok(())
}
