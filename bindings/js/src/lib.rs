//! The WebAssembly build of rotlang for the npm package `rotlang` (`bindings/js`).
//!
//! Plain C-ABI exports and a small hand-written JS wrapper (`rotlang.js`) rather than
//! wasm-bindgen: no CLI tool whose version must match the crate, and a smaller module.
//! The convention, for every call: JavaScript copies the template (UTF-8) and a JSON
//! request into memory from `rotlang_alloc`, calls the export, which returns 0 (success)
//! or 1 (failure); the JSON answer (or the failure) is at `rotlang_out_ptr` /
//! `rotlang_out_len` until the next call. `expand` also leaves its typed arrays at
//! `rotlang_angles_ptr` etc. Nothing panics on bad input; were something to, the wasm
//! traps and the wrapper turns the trap into a JS exception and starts a fresh instance.

pub mod api;
pub mod diagnostics;
pub mod ffi;
pub mod json;
pub mod options;
#[cfg(feature = "full")]
pub mod part;
pub mod utf16;

use crate::json::Value;

/// Why a call failed: the JS wrapper throws a `RotlangError` with these fields.
#[derive(Debug)]
pub struct Failure {
    /// `template` (errors in the template: see `diagnostics`), `model`, `options`,
    /// `limit` (too large an answer), `unavailable` (not in this build).
    pub kind: &'static str,
    pub message: String,
    pub diagnostics: Option<Value>,
}

impl Failure {
    pub fn options(message: impl Into<String>) -> Failure {
        Failure {
            kind: "options",
            message: message.into(),
            diagnostics: None,
        }
    }

    pub fn model(message: impl Into<String>) -> Failure {
        Failure {
            kind: "model",
            message: message.into(),
            diagnostics: None,
        }
    }

    pub fn limit(message: impl Into<String>) -> Failure {
        Failure {
            kind: "limit",
            message: message.into(),
            diagnostics: None,
        }
    }

    pub fn unavailable(message: impl Into<String>) -> Failure {
        Failure {
            kind: "unavailable",
            message: message.into(),
            diagnostics: None,
        }
    }

    pub fn template(message: String, diagnostics: Value) -> Failure {
        Failure {
            kind: "template",
            message,
            diagnostics: Some(diagnostics),
        }
    }

    pub fn to_json(&self) -> Value {
        obj!({
            "kind": self.kind,
            "message": self.message,
            "diagnostics": self.diagnostics,
        })
    }
}
