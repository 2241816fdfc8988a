//! The protocol glue: state, capabilities, and one handler per request, each delegating
//! to its feature module.

use std::collections::HashMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Arc, Mutex, MutexGuard};

use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::*;
use tower_lsp_server::{Client, LanguageServer, LspService, Server};

use crate::document::{Document, Kind};
use crate::position::{Encoding, Positions};
use crate::settings::ModelSettings;
use crate::{
    code_actions, completion, diagnostics, formatting, hover, inlay_hints, markup, semantic_tokens,
    symbols,
};

#[derive(Default)]
struct State {
    documents: HashMap<Uri, Arc<Document>>,
    encoding: Encoding,
    model: ModelSettings,
    inlay_refresh: bool,
    /// The client answers `workspace/configuration` (the pull model).
    pull_configuration: bool,
    /// The client lets the server register `workspace/didChangeConfiguration` (clients
    /// built on vscode-languageclient send it only once registered).
    register_configuration: bool,
    /// The client asked for plain text in hovers / completion documentation.
    plain_hover: bool,
    plain_documentation: bool,
    /// Problems with the initialization options, reported once the client is initialized
    /// (the protocol lets a server speak first only then).
    pending_warnings: Vec<String>,
    /// Invalid settings were shown in a message box already (the log gets every time).
    shown_settings_warning: bool,
}

pub struct Backend {
    client: Client,
    state: Arc<Mutex<State>>,
}

impl Backend {
    pub fn new(client: Client) -> Backend {
        Backend {
            client,
            state: Arc::new(Mutex::new(State::default())),
        }
    }

    fn state(&self) -> MutexGuard<'_, State> {
        lock(&self.state)
    }

    /// Ask the client for the `rotlang` section (clients that push settings through
    /// didChangeConfiguration send nothing useful there, and VS Code-style clients send
    /// `null` and expect a pull). Spawned, so a client that never answers blocks nothing.
    fn pull_configuration(&self) {
        if !self.state().pull_configuration {
            return;
        }
        let client = self.client.clone();
        let state = self.state.clone();
        tokio::spawn(async move {
            let item = ConfigurationItem {
                scope_uri: None,
                section: Some("rotlang".into()),
            };
            if let Ok(values) = client.configuration(vec![item]).await
                && let Some(value) = values.first()
                // `null`: the client has no such section; what it gave before stays.
                && !value.is_null()
            {
                let section = ModelSettings::section(value).unwrap_or(value);
                let (rejected, refresh) = {
                    let mut state = lock(&state);
                    (state.model.replace(section), state.inlay_refresh)
                };
                report_settings(&client, &state, rejected).await;
                if refresh {
                    // Hints depend on the model; the answer does not matter.
                    let _ = client.inlay_hint_refresh().await;
                }
            }
        });
    }

    /// The document (shared, so no lock is held while computing), the encoding and model.
    fn snapshot(&self, uri: &Uri) -> Option<(Arc<Document>, Encoding, ModelSettings)> {
        let state = self.state();
        let doc = state.documents.get(uri)?.clone();
        Some((doc, state.encoding, state.model))
    }

    /// Register for `workspace/didChangeConfiguration` where the client allows it.
    /// Spawned: the answer is awaited, and nothing else should wait for it.
    fn register_configuration(&self) {
        if !self.state().register_configuration {
            return;
        }
        let client = self.client.clone();
        tokio::spawn(async move {
            let registration = Registration {
                id: "rotlang-configuration".into(),
                method: "workspace/didChangeConfiguration".into(),
                register_options: None,
            };
            if let Err(e) = client.register_capability(vec![registration]).await {
                client
                    .log_message(
                        MessageType::INFO,
                        format!("rotlang: could not register for settings changes: {e}"),
                    )
                    .await;
            }
        });
    }

    async fn publish(&self, uri: Uri, doc: Arc<Document>, encoding: Encoding) {
        let settings = self.state().model;
        let Some(diags) = guard(|| {
            let pos = Positions::new(&doc.text, encoding);
            let mut diags = diagnostics::diagnostics(&doc, &uri, &pos);
            diags.extend(crate::compat::diagnostics(&doc, &uri, &pos, &settings));
            diags
        }) else {
            return;
        };
        // A newer edit may have arrived while computing: it publishes its own.
        let current = self.state().documents.get(&uri).map(|d| d.version);
        if current == Some(doc.version) {
            self.client
                .publish_diagnostics(uri, diags, Some(doc.version))
                .await;
        }
    }

    async fn open(&self, uri: Uri, text: String, kind: Kind, version: i32) {
        let limit = self.state().model.max_document_bytes;
        if text.len() > limit {
            let doc = Arc::new(Document::too_large(text.len(), limit, kind, version));
            drop(text);
            let encoding = {
                let mut state = self.state();
                state.documents.insert(uri.clone(), doc.clone());
                state.encoding
            };
            self.publish(uri, doc, encoding).await;
            return;
        }
        let Some(doc) = guard(|| Arc::new(Document::new(text, kind, version))) else {
            return;
        };
        let encoding = {
            let mut state = self.state();
            state.documents.insert(uri.clone(), doc.clone());
            state.encoding
        };
        self.publish(uri, doc, encoding).await;
    }
}

fn lock(state: &Mutex<State>) -> MutexGuard<'_, State> {
    // A panic in one handler must not take the state down with it for the others.
    state
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Run a feature, turning a panic (a bug, never expected) into "no answer" instead of a
/// dead server.
fn guard<T>(f: impl FnOnce() -> T) -> Option<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(v) => Some(v),
        Err(_) => {
            eprintln!("rotlang-lsp: internal error (panic) while answering; see above");
            None
        }
    }
}

/// Tell the user about settings that were not accepted: every time in the log, once per
/// session in a message box (a wrong value in a settings file should be seen, but not
/// pop up on every keystroke of a settings editor).
async fn report_settings(client: &Client, state: &Mutex<State>, rejected: Vec<String>) {
    if rejected.is_empty() {
        return;
    }
    let text = format!("rotlang: ignored invalid settings: {}", rejected.join("; "));
    client.log_message(MessageType::WARNING, &text).await;
    let first = !std::mem::replace(&mut lock(state).shown_settings_warning, true);
    if first {
        client
            .show_message(
                MessageType::WARNING,
                format!("{text} (the log lists every later change)"),
            )
            .await;
    }
}

fn internal() -> Error {
    Error::internal_error()
}

impl LanguageServer for Backend {
    async fn initialize(&self, params: InitializeParams) -> Result<InitializeResult> {
        let offered = params
            .capabilities
            .general
            .as_ref()
            .and_then(|g| g.position_encodings.as_deref());
        let encoding = Encoding::negotiate(offered);
        let pull_configuration = params
            .capabilities
            .workspace
            .as_ref()
            .and_then(|w| w.configuration)
            .unwrap_or(false);
        let inlay_refresh = params
            .capabilities
            .workspace
            .as_ref()
            .and_then(|w| w.inlay_hint.as_ref())
            .and_then(|i| i.refresh_support)
            .unwrap_or(false);
        let register_configuration = params
            .capabilities
            .workspace
            .as_ref()
            .and_then(|w| w.did_change_configuration.as_ref())
            .and_then(|d| d.dynamic_registration)
            .unwrap_or(false);
        let text_document = params.capabilities.text_document.as_ref();
        let plain_hover = markup::wants_plain(
            text_document
                .and_then(|t| t.hover.as_ref())
                .and_then(|h| h.content_format.as_deref()),
        );
        let plain_documentation = markup::wants_plain(
            text_document
                .and_then(|t| t.completion.as_ref())
                .and_then(|c| c.completion_item.as_ref())
                .and_then(|i| i.documentation_format.as_deref()),
        );
        {
            let mut state = self.state();
            state.encoding = encoding;
            state.inlay_refresh = inlay_refresh;
            state.pull_configuration = pull_configuration;
            state.register_configuration = register_configuration;
            state.plain_hover = plain_hover;
            state.plain_documentation = plain_documentation;
            if let Some(section) = params
                .initialization_options
                .as_ref()
                .and_then(ModelSettings::section)
            {
                state.pending_warnings = state.model.replace(section);
            }
        }
        Ok(InitializeResult {
            capabilities: capabilities(encoding),
            server_info: Some(ServerInfo {
                name: "rotlang-lsp".into(),
                version: Some(env!("CARGO_PKG_VERSION").into()),
            }),
            offset_encoding: None,
        })
    }

    async fn initialized(&self, _: InitializedParams) {
        let warnings = std::mem::take(&mut self.state().pending_warnings);
        report_settings(&self.client, &self.state, warnings).await;
        self.register_configuration();
        self.pull_configuration();
    }

    async fn shutdown(&self) -> Result<()> {
        Ok(())
    }

    async fn did_open(&self, params: DidOpenTextDocumentParams) {
        let d = params.text_document;
        let Some(kind) = Kind::detect(&d.language_id, d.uri.as_str()) else {
            return; // not a template file: requests on it answer null
        };
        self.open(d.uri, d.text, kind, d.version).await;
    }

    async fn did_change(&self, params: DidChangeTextDocumentParams) {
        let uri = params.text_document.uri;
        let Some((old, encoding, _)) = self.snapshot(&uri) else {
            return; // a change to a document never opened: nothing to apply it to
        };
        // Full sync sends the whole text; ranged changes are applied too, in case a
        // client sends them anyway.
        let mut text: Option<String> = None;
        for change in params.content_changes {
            match change.range {
                None => text = Some(change.text),
                Some(range) => {
                    let mut current = text.take().unwrap_or_else(|| old.text.clone());
                    if let Some(span) = Positions::new(&current, encoding).span(range) {
                        current.replace_range(span.range(), &change.text);
                    }
                    text = Some(current);
                }
            }
        }
        let Some(text) = text else { return };
        self.open(uri, text, old.kind, params.text_document.version)
            .await;
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        let uri = params.text_document.uri;
        self.state().documents.remove(&uri);
        // Clear what was shown: a closed document has no problems to display.
        self.client.publish_diagnostics(uri, Vec::new(), None).await;
    }

    async fn did_change_configuration(&self, params: DidChangeConfigurationParams) {
        // Pushed settings win; clients that push nothing useful (`null`, or only other
        // tools' sections, as VS Code-style clients do) are asked.
        let Some(section) = ModelSettings::section(&params.settings) else {
            self.pull_configuration();
            return;
        };
        let before = self.state().model.compat;
        let rejected = self.state().model.replace(section);
        report_settings(&self.client, &self.state, rejected).await;
        if self.state().model.compat != before {
            // The compat findings are part of every document's diagnostics.
            let (docs, encoding) = {
                let state = self.state();
                let docs: Vec<_> = state
                    .documents
                    .iter()
                    .map(|(u, d)| (u.clone(), d.clone()))
                    .collect();
                (docs, state.encoding)
            };
            for (uri, doc) in docs {
                self.publish(uri, doc, encoding).await;
            }
        }
        if self.state().inlay_refresh {
            // Hints depend on the model; the answer does not matter.
            let _ = self.client.inlay_hint_refresh().await;
        }
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        let p = params.text_document_position_params;
        let plain = self.state().plain_hover;
        let Some((doc, encoding, model)) = self.snapshot(&p.text_document.uri) else {
            return Ok(None);
        };
        guard(|| {
            let pos = Positions::new(&doc.text, encoding);
            let offset = pos.offset(p.position)?;
            let mut hover = hover::hover(&doc, offset, &model, &pos)?;
            if plain && let HoverContents::Markup(m) = &mut hover.contents {
                *m = markup::content(std::mem::take(&mut m.value), true);
            }
            Some(hover)
        })
        .ok_or_else(internal)
    }

    async fn completion(&self, params: CompletionParams) -> Result<Option<CompletionResponse>> {
        let p = params.text_document_position;
        let plain = self.state().plain_documentation;
        let Some((doc, encoding, _)) = self.snapshot(&p.text_document.uri) else {
            return Ok(None);
        };
        guard(|| {
            let pos = Positions::new(&doc.text, encoding);
            let offset = pos.offset(p.position)?;
            let mut items = completion::completion(&doc, offset, &pos)?;
            if plain {
                for item in &mut items {
                    if let Some(Documentation::MarkupContent(m)) = &mut item.documentation {
                        *m = markup::content(std::mem::take(&mut m.value), true);
                    }
                }
            }
            Some(CompletionResponse::Array(items))
        })
        .ok_or_else(internal)
    }

    async fn semantic_tokens_full(
        &self,
        params: SemanticTokensParams,
    ) -> Result<Option<SemanticTokensResult>> {
        let Some((doc, encoding, _)) = self.snapshot(&params.text_document.uri) else {
            return Ok(None);
        };
        guard(|| {
            let pos = Positions::new(&doc.text, encoding);
            Some(SemanticTokensResult::Tokens(semantic_tokens::tokens(
                &doc, &pos,
            )))
        })
        .ok_or_else(internal)
    }

    async fn formatting(&self, params: DocumentFormattingParams) -> Result<Option<Vec<TextEdit>>> {
        let Some((doc, encoding, settings)) = self.snapshot(&params.text_document.uri) else {
            return Ok(None);
        };
        let keep_orcaslicer = settings.compat.applies_to(doc.kind);
        guard(|| {
            formatting::formatting(&doc, &Positions::new(&doc.text, encoding), keep_orcaslicer)
        })
        .ok_or_else(internal)
    }

    async fn inlay_hint(&self, params: InlayHintParams) -> Result<Option<Vec<InlayHint>>> {
        let Some((doc, encoding, model)) = self.snapshot(&params.text_document.uri) else {
            return Ok(None);
        };
        guard(|| {
            let pos = Positions::new(&doc.text, encoding);
            let range = pos.span(params.range)?;
            Some(inlay_hints::inlay_hints(&doc, range, &model, &pos))
        })
        .ok_or_else(internal)
    }

    async fn code_action(&self, params: CodeActionParams) -> Result<Option<CodeActionResponse>> {
        let uri = params.text_document.uri;
        let Some((doc, encoding, _)) = self.snapshot(&uri) else {
            return Ok(None);
        };
        guard(|| {
            let pos = Positions::new(&doc.text, encoding);
            let range = pos.span(params.range)?;
            Some(code_actions::code_actions(&doc, &uri, range, &pos))
        })
        .ok_or_else(internal)
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        let Some((doc, encoding, model)) = self.snapshot(&params.text_document.uri) else {
            return Ok(None);
        };
        guard(|| {
            let pos = Positions::new(&doc.text, encoding);
            Some(DocumentSymbolResponse::Nested(symbols::symbols(
                &doc, &model, &pos,
            )))
        })
        .ok_or_else(internal)
    }
}

pub fn capabilities(encoding: Encoding) -> ServerCapabilities {
    ServerCapabilities {
        position_encoding: Some(encoding.kind()),
        text_document_sync: Some(TextDocumentSyncCapability::Options(
            TextDocumentSyncOptions {
                open_close: Some(true),
                change: Some(TextDocumentSyncKind::FULL),
                ..TextDocumentSyncOptions::default()
            },
        )),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        completion_provider: Some(CompletionOptions::default()),
        semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
            SemanticTokensOptions {
                legend: semantic_tokens::legend(),
                full: Some(SemanticTokensFullOptions::Bool(true)),
                range: None,
                work_done_progress_options: WorkDoneProgressOptions::default(),
            },
        )),
        document_formatting_provider: Some(OneOf::Left(true)),
        inlay_hint_provider: Some(OneOf::Left(true)),
        code_action_provider: Some(CodeActionProviderCapability::Options(CodeActionOptions {
            code_action_kinds: Some(vec![CodeActionKind::QUICKFIX]),
            ..CodeActionOptions::default()
        })),
        document_symbol_provider: Some(OneOf::Left(true)),
        ..ServerCapabilities::default()
    }
}

/// Run the server on stdin/stdout until the client says `exit` or closes the stream.
pub async fn run_stdio() {
    serve(tokio::io::stdin(), tokio::io::stdout()).await;
}

/// Run the server on any pair of byte streams, behind the framing guard: stdio in
/// `run_stdio`, in-memory buffers in the fuzz target `lsp_framing`.
pub async fn serve<I, O>(input: I, output: O)
where
    I: tokio::io::AsyncRead + Unpin + Send + 'static,
    O: tokio::io::AsyncWrite + Unpin,
{
    crate::transport::serve(input, output, |input, output| async move {
        let (service, socket) = LspService::new(Backend::new);
        Server::new(input, output, socket).serve(service).await;
    })
    .await;
}
