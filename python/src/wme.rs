//! SML's working-memory elements as Python sees them: `WMElement` and its kinds
//! `Identifier`, `IntElement`, `FloatElement` and `StringElement`, read from the client's
//! copy of the agent's links.

use crate::errors::SoarError;
use crate::mirror::{CValue, Mirror};
use crate::shared::AgentShared;
use pyo3::prelude::*;
use pyo3::PyClassInitializer;
use std::sync::Arc;

/// A working-memory element: `(identifier ^attribute value)`.
#[pyclass(subclass, module = "rusoar._rusoar", name = "WMElement")]
pub struct WMElement {
    pub(crate) agent: Arc<AgentShared>,
    pub(crate) key: usize,
}

/// A WME whose value is an identifier; it stands for that identifier, too.
#[pyclass(extends = WMElement, module = "rusoar._rusoar", name = "Identifier")]
pub struct Identifier;

/// A WME whose value is an integer.
#[pyclass(extends = WMElement, module = "rusoar._rusoar", name = "IntElement")]
pub struct IntElement;

/// A WME whose value is a float.
#[pyclass(extends = WMElement, module = "rusoar._rusoar", name = "FloatElement")]
pub struct FloatElement;

/// A WME whose value is a string.
#[pyclass(extends = WMElement, module = "rusoar._rusoar", name = "StringElement")]
pub struct StringElement;

/// The Python object for WME `w` of `agent`'s copy, of the class its value calls for.
pub fn make(py: Python<'_>, agent: &Arc<AgentShared>, w: usize) -> PyResult<Py<PyAny>> {
    let value = agent.mirror().wmes[w].value.clone();
    let base = PyClassInitializer::from(WMElement {
        agent: Arc::clone(agent),
        key: w,
    });
    Ok(match value {
        CValue::Id(_) => Py::new(py, base.add_subclass(Identifier))?.into_any(),
        CValue::Int(_) => Py::new(py, base.add_subclass(IntElement))?.into_any(),
        CValue::Float(_) => Py::new(py, base.add_subclass(FloatElement))?.into_any(),
        CValue::Str(_) => Py::new(py, base.add_subclass(StringElement))?.into_any(),
    })
}

/// A value for a new WME.
pub enum NewValue {
    /// A constant.
    Plain(CValue),
    /// A new identifier.
    NewId,
    /// An identifier the client already has (an index into the copy's identifiers).
    Shared(usize),
}

/// Makes `(parent ^attr value)` in the client's copy; it reaches the kernel at its next
/// input phase.
pub fn create(
    py: Python<'_>,
    agent: &Arc<AgentShared>,
    parent: usize,
    attr: &str,
    value: NewValue,
) -> PyResult<Py<PyAny>> {
    agent.check()?;
    let tt = agent.kernel.next_timetag();
    let w = {
        let mut m = agent.mirror();
        match value {
            NewValue::Plain(v) => m.add(parent, attr, v, tt),
            NewValue::NewId => m.add_object(parent, attr, agent.kernel.next_id_name(attr), tt),
            NewValue::Shared(o) => m.add(parent, attr, CValue::Id(o), tt),
        }
    };
    make(py, agent, w)
}

impl WMElement {
    /// Runs `f` on the copy and this WME, once sure both are there.
    pub(crate) fn read<R>(&self, f: impl FnOnce(&Mirror, usize) -> R) -> PyResult<R> {
        self.agent.check()?;
        let m = self.agent.mirror();
        if !m.wmes[self.key].alive {
            return Err(SoarError::new_err(format!(
                "the WME ^{} was destroyed (or left the output-link): it cannot be used again",
                m.wmes[self.key].attr
            )));
        }
        Ok(f(&m, self.key))
    }

    /// The identifier this WME's value names (an index into the copy's identifiers).
    pub(crate) fn object(&self) -> PyResult<usize> {
        self.read(|m, w| m.value_obj(w))?
            .ok_or_else(|| SoarError::new_err("this WME's value is not an identifier"))
    }
}

#[pymethods]
impl WMElement {
    /// The attribute.
    #[pyo3(name = "GetAttribute")]
    fn get_attribute(&self) -> PyResult<String> {
        self.read(|m, w| m.wmes[w].attr.clone())
    }

    /// The value as text (an identifier's name, a float as SML prints it).
    #[pyo3(name = "GetValueAsString")]
    fn get_value_as_string(&self) -> PyResult<String> {
        self.read(|m, w| m.value_text(w))
    }

    /// `id`, `int`, `double` or `string`.
    #[pyo3(name = "GetValueType")]
    fn get_value_type(&self) -> PyResult<&'static str> {
        self.read(|m, w| match m.wmes[w].value {
            CValue::Id(_) => "id",
            CValue::Int(_) => "int",
            CValue::Float(_) => "double",
            CValue::Str(_) => "string",
        })
    }

    /// The timetag: negative for the client's WMEs, the kernel's for the output-link's.
    #[pyo3(name = "GetTimeTag")]
    fn get_time_tag(&self) -> PyResult<i64> {
        self.read(|m, w| m.wmes[w].timetag)
    }

    /// The name of the identifier this WME hangs from.
    #[pyo3(name = "GetIdentifierName")]
    fn get_identifier_name(&self) -> PyResult<String> {
        self.read(|m, w| m.objs[m.wmes[w].parent].name.clone())
    }

    /// Whether the value is an identifier.
    #[pyo3(name = "IsIdentifier")]
    fn is_identifier(&self) -> PyResult<bool> {
        self.read(|m, w| m.value_obj(w).is_some())
    }

    /// Whether the WME came onto the output-link since the last `ClearOutputLinkChanges`.
    #[pyo3(name = "IsJustAdded")]
    fn is_just_added(&self) -> PyResult<bool> {
        self.read(|m, w| m.wmes[w].just_added)
    }

    /// This WME as an `Identifier`, or None.
    #[pyo3(name = "ConvertToIdentifier")]
    fn convert_to_identifier(slf: &Bound<'_, Self>) -> Option<Py<PyAny>> {
        slf.is_instance_of::<Identifier>()
            .then(|| slf.clone().into_any().unbind())
    }

    /// This WME as an `IntElement`, or None.
    #[pyo3(name = "ConvertToIntElement")]
    fn convert_to_int_element(slf: &Bound<'_, Self>) -> Option<Py<PyAny>> {
        slf.is_instance_of::<IntElement>()
            .then(|| slf.clone().into_any().unbind())
    }

    /// This WME as a `FloatElement`, or None.
    #[pyo3(name = "ConvertToFloatElement")]
    fn convert_to_float_element(slf: &Bound<'_, Self>) -> Option<Py<PyAny>> {
        slf.is_instance_of::<FloatElement>()
            .then(|| slf.clone().into_any().unbind())
    }

    /// This WME as a `StringElement`, or None.
    #[pyo3(name = "ConvertToStringElement")]
    fn convert_to_string_element(slf: &Bound<'_, Self>) -> Option<Py<PyAny>> {
        slf.is_instance_of::<StringElement>()
            .then(|| slf.clone().into_any().unbind())
    }

    /// The value: an int, a float, a string, or an identifier's name.
    #[pyo3(name = "GetValue")]
    fn get_value(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v = self.read(|m, w| m.wmes[w].value.clone())?;
        Ok(match v {
            CValue::Int(i) => i.into_pyobject(py)?.into_any().unbind(),
            CValue::Float(f) => f.into_pyobject(py)?.into_any().unbind(),
            CValue::Str(s) => s.into_pyobject(py)?.into_any().unbind(),
            CValue::Id(_) => self
                .get_value_as_string()?
                .into_pyobject(py)?
                .into_any()
                .unbind(),
        })
    }

    /// Whether the WME is still there (not destroyed, still on the output-link).
    fn is_valid(&self) -> bool {
        self.agent.check().is_ok() && self.agent.mirror().wmes[self.key].alive
    }

    fn __repr__(&self) -> String {
        let m = self.agent.mirror();
        let w = &m.wmes[self.key];
        format!(
            "({} ^{} {})",
            m.objs[w.parent].name,
            w.attr,
            m.value_text(self.key)
        )
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        match other.cast::<WMElement>() {
            Ok(o) => {
                let o = o.borrow();
                Arc::ptr_eq(&o.agent, &self.agent) && o.key == self.key
            }
            Err(_) => false,
        }
    }

    fn __hash__(&self) -> u64 {
        self.key as u64
    }
}

#[pymethods]
impl Identifier {
    /// The number of WMEs of this identifier.
    #[pyo3(name = "GetNumberChildren")]
    fn get_number_children(slf: PyRef<'_, Self>) -> PyResult<usize> {
        let base = slf.as_super();
        let o = base.object()?;
        Ok(base.agent.mirror().objs[o].children.len())
    }

    /// WME `index` of this identifier, or None.
    #[pyo3(name = "GetChild")]
    fn get_child(slf: PyRef<'_, Self>, py: Python<'_>, index: i64) -> PyResult<Option<Py<PyAny>>> {
        let base = slf.as_super();
        let o = base.object()?;
        let w = usize::try_from(index)
            .ok()
            .and_then(|i| base.agent.mirror().objs[o].children.get(i).copied());
        w.map(|w| make(py, &base.agent, w)).transpose()
    }

    /// The `index`-th WME of this identifier with attribute `attr`, or None.
    #[pyo3(name = "FindByAttribute")]
    #[pyo3(signature = (attr, index = 0))]
    fn find_by_attribute(
        slf: PyRef<'_, Self>,
        py: Python<'_>,
        attr: &str,
        index: i64,
    ) -> PyResult<Option<Py<PyAny>>> {
        let base = slf.as_super();
        let o = base.object()?;
        let w = usize::try_from(index)
            .ok()
            .and_then(|i| base.agent.mirror().find(o, attr).nth(i));
        w.map(|w| make(py, &base.agent, w)).transpose()
    }

    /// The value, as text, of this identifier's first WME with attribute `attr`, or None.
    #[pyo3(name = "GetParameterValue")]
    fn get_parameter_value(slf: PyRef<'_, Self>, attr: &str) -> PyResult<Option<String>> {
        let base = slf.as_super();
        let o = base.object()?;
        let m = base.agent.mirror();
        let w = m.find(o, attr).next();
        Ok(w.map(|w| m.value_text(w)))
    }

    /// The command's name: the attribute of its WME on the output-link.
    #[pyo3(name = "GetCommandName")]
    fn get_command_name(slf: PyRef<'_, Self>) -> PyResult<String> {
        slf.as_super().get_attribute()
    }

    /// Adds `^status complete` to this command.
    #[pyo3(name = "AddStatusComplete")]
    fn add_status_complete(slf: PyRef<'_, Self>, py: Python<'_>) -> PyResult<()> {
        let base = slf.as_super();
        let o = base.object()?;
        let v = NewValue::Plain(CValue::Str("complete".to_string()));
        create(py, &base.agent, o, "status", v).map(|_| ())
    }

    /// Adds `^status error` to this command.
    #[pyo3(name = "AddStatusError")]
    fn add_status_error(slf: PyRef<'_, Self>, py: Python<'_>) -> PyResult<()> {
        let base = slf.as_super();
        let o = base.object()?;
        let v = NewValue::Plain(CValue::Str("error".to_string()));
        create(py, &base.agent, o, "status", v).map(|_| ())
    }

    /// Adds `(this ^attr <new identifier>)`.
    #[pyo3(name = "CreateIdWME")]
    fn create_id_wme(slf: PyRef<'_, Self>, py: Python<'_>, attr: &str) -> PyResult<Py<PyAny>> {
        let base = slf.as_super();
        create(py, &base.agent, base.object()?, attr, NewValue::NewId)
    }

    /// Adds `(this ^attr value)` with a string.
    #[pyo3(name = "CreateStringWME")]
    fn create_string_wme(
        slf: PyRef<'_, Self>,
        py: Python<'_>,
        attr: &str,
        value: String,
    ) -> PyResult<Py<PyAny>> {
        let base = slf.as_super();
        let v = NewValue::Plain(CValue::Str(value));
        create(py, &base.agent, base.object()?, attr, v)
    }

    /// Adds `(this ^attr value)` with an integer.
    #[pyo3(name = "CreateIntWME")]
    fn create_int_wme(
        slf: PyRef<'_, Self>,
        py: Python<'_>,
        attr: &str,
        value: i64,
    ) -> PyResult<Py<PyAny>> {
        let base = slf.as_super();
        let v = NewValue::Plain(CValue::Int(value));
        create(py, &base.agent, base.object()?, attr, v)
    }

    /// Adds `(this ^attr value)` with a float.
    #[pyo3(name = "CreateFloatWME")]
    fn create_float_wme(
        slf: PyRef<'_, Self>,
        py: Python<'_>,
        attr: &str,
        value: f64,
    ) -> PyResult<Py<PyAny>> {
        let base = slf.as_super();
        let v = NewValue::Plain(CValue::Float(value));
        create(py, &base.agent, base.object()?, attr, v)
    }

    /// Adds `(this ^attr shared)`, whose value is an identifier the client already has.
    #[pyo3(name = "CreateSharedIdWME")]
    fn create_shared_id_wme(
        slf: PyRef<'_, Self>,
        py: Python<'_>,
        attr: &str,
        shared: PyRef<'_, Identifier>,
    ) -> PyResult<Py<PyAny>> {
        let base = slf.as_super();
        let o = shared.as_super().object()?;
        create(py, &base.agent, base.object()?, attr, NewValue::Shared(o))
    }

    fn __len__(slf: PyRef<'_, Self>) -> PyResult<usize> {
        Self::get_number_children(slf)
    }

    fn __iter__(slf: PyRef<'_, Self>, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let base = slf.as_super();
        let o = base.object()?;
        let children: Vec<usize> = base.agent.mirror().objs[o].children.clone();
        let items = children
            .into_iter()
            .map(|w| make(py, &base.agent, w))
            .collect::<PyResult<Vec<_>>>()?;
        Ok(pyo3::types::PyList::new(py, items)?
            .try_iter()?
            .into_any()
            .unbind())
    }
}
