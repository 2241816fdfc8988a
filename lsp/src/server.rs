//! The protocol glue: state, capabilities, and one handler per request, each delegating
//! to its feature module.

use std::collections::HashMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex, MutexGuard};

use tokio::sync::watch;
use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::*;
use tower_lsp_server::{Client, LanguageServer, LspService, Server};

use crate::document::{Document, Kind};
use crate::position::{Encoding, Positions};
use crate::settings::ModelSettings;
use crate::sync::{self, Applied, Open};
use crate::{
    code_actions, completion, diagnostics, formatting, hover, inlay_hints, markup, semantic_tokens,
    symbols,
};

#[derive(Default)]
struct State {
    documents: HashMap<Uri, Open>,
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

/// The server's handle: cheap to clone into the tasks that analyse documents.
#[derive(Clone)]
pub struct Backend {
    client: Client,
    state: Arc<Mutex<State>>,
    /// Bumped whenever an analysis is installed (or a document changes state), so that
    /// requests waiting for the current version wake up and look again.
    analysed: Arc<watch::Sender<u64>>,
}

impl Backend {
    pub fn new(client: Client) -> Backend {
        Backend {
            client,
            state: Arc::new(Mutex::new(State::default())),
            analysed: Arc::new(watch::channel(0).0),
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
        let this = self.clone();
        tokio::spawn(async move {
            let item = ConfigurationItem {
                scope_uri: None,
                section: Some("rotlang".into()),
            };
            if let Ok(values) = this.client.configuration(vec![item]).await
                && let Some(value) = values.first()
                // `null`: the client has no such section; what it gave before stays.
                && !value.is_null()
            {
                let section = ModelSettings::section(value).unwrap_or(value);
                this.apply_settings(section).await;
            }
        });
    }

    /// Take a new `rotlang` section: report what was refused, republish the diagnostics
    /// when they depend on what changed, refresh inlay hints.
    async fn apply_settings(&self, section: &serde_json::Value) {
        let (before, rejected) = {
            let mut state = self.state();
            let before = state.model;
            (before, state.model.replace(section))
        };
        report_settings(&self.client, &self.state, rejected).await;
        let (after, refresh) = {
            let state = self.state();
            (state.model, state.inlay_refresh)
        };
        if after != before {
            // The compat findings are part of the diagnostics, and a `.rot` file's are
            // computed on the settings' model.
            let uris: Vec<Uri> = self.state().documents.keys().cloned().collect();
            for uri in uris {
                self.schedule_publish(uri);
            }
        }
        if refresh {
            // Hints depend on the model; the answer does not matter.
            let _ = self.client.inlay_hint_refresh().await;
        }
    }

    /// The analysis of a document's latest version, with the encoding and settings; waits
    /// while it is being computed (a `$/cancelRequest` ends the wait: the request is then
    /// answered as cancelled). `None` when the document is not open, not a template file,
    /// or out of sync.
    async fn current(&self, uri: &Uri) -> Option<(Arc<Document>, Encoding, ModelSettings)> {
        let mut changes = self.analysed.subscribe();
        // The version the request was made against: later edits do not make it wait longer.
        let mut wanted = self.state().documents.get(uri)?.version;
        loop {
            {
                let state = self.state();
                let open = state.documents.get(uri)?;
                if open.out_of_sync.is_some() {
                    return None;
                }
                // A client may send a lower version next (versions should rise, but the
                // server must not hang on one that does not): then the latest is the one
                // to wait for, or no analysis would ever be between the two.
                wanted = wanted.min(open.version);
                if let Some(doc) = &open.analysed
                    && doc.version >= wanted
                    && doc.version <= open.version
                {
                    return Some((doc.clone(), state.encoding, state.model));
                }
            }
            changes.changed().await.ok()?;
        }
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

    /// Publish the diagnostics of a document's latest analysis, in the background: one
    /// publishing task per document, which takes the latest analysis each time round
    /// (the OrcaSlicer lint of a long profile takes seconds: analyses go on meanwhile, and
    /// the versions analysed in between are never linted).
    fn schedule_publish(&self, uri: Uri) {
        {
            let mut state = self.state();
            let Some(open) = state.documents.get_mut(&uri) else {
                return;
            };
            if open.publishing {
                return; // the running task takes the latest when it is done
            }
            open.publishing = true;
        }
        let this = self.clone();
        tokio::spawn(async move { this.publish_task(uri).await });
    }

    async fn publish_task(&self, uri: Uri) {
        loop {
            let next = {
                let mut state = self.state();
                let settings = state.model;
                let Some(open) = state.documents.get_mut(&uri) else {
                    return;
                };
                let doc = open
                    .current()
                    .filter(|d| open.published != Some((d.version, settings)))
                    .cloned();
                if doc.is_none() {
                    open.publishing = false;
                }
                doc.map(|d| (d, settings))
            };
            let Some((doc, settings)) = next else {
                return;
            };
            let version = doc.version;
            self.publish(uri.clone(), doc).await;
            if let Some(open) = self.state().documents.get_mut(&uri) {
                open.published = Some((version, settings));
            }
        }
    }

    /// Publish a document's diagnostics (computed off the main thread: a large document
    /// takes a while), unless a newer version has arrived meanwhile: it publishes its own.
    async fn publish(&self, uri: Uri, doc: Arc<Document>) {
        let (settings, encoding, latest) = {
            let state = self.state();
            let latest = state.documents.get(&uri).map(|o| o.latest.clone());
            (state.model, state.encoding, latest)
        };
        let version = doc.version;
        // A newer text has come: its analysis publishes (this one would not be shown).
        let stale = move || {
            latest
                .as_ref()
                .is_none_or(|l| l.load(Ordering::Relaxed) != version)
        };
        let job = {
            let uri = uri.clone();
            move || {
                guard(move || {
                    let mut diags = {
                        let pos = Positions::new(&doc.text, encoding);
                        let mut diags = diagnostics::diagnostics(&doc, &uri, &pos);
                        if let Some(found) = crate::compat::cached_only(&doc, &settings) {
                            diags.extend(crate::compat::diagnostics(&doc, &found, &uri, &pos));
                            return Some(diags);
                        }
                        diags
                    };
                    // The lint reads its own copy of the templates: the analysis is not
                    // held meanwhile, so the next one can be made from it in place.
                    if stale() {
                        return None; // a lint of seconds for nothing
                    }
                    let inputs = crate::compat::inputs(&doc, &settings);
                    let weak = Arc::downgrade(&doc);
                    drop(doc);
                    let large = crate::compat::size(&inputs) > LARGE;
                    let found = Arc::new(crate::compat::run(inputs));
                    if large {
                        // The lint of a long template allocates about 50 bytes per byte on
                        // this thread: handed back now, not kept in its arena.
                        crate::memory::release();
                    }
                    // Gone: a newer analysis was made from it, and publishes its own.
                    let doc = weak.upgrade()?;
                    crate::compat::store(&doc, &settings, found.clone());
                    let pos = Positions::new(&doc.text, encoding);
                    diags.extend(crate::compat::diagnostics(&doc, &found, &uri, &pos));
                    Some(diags)
                })
                .flatten()
            }
        };
        let Ok(Some(diags)) = tokio::task::spawn_blocking(job).await else {
            return;
        };
        let current = self
            .state()
            .documents
            .get(&uri)
            .map(|o| (o.version, o.out_of_sync.is_some()));
        if current == Some((version, false)) {
            self.client
                .publish_diagnostics(uri, diags, Some(version))
                .await;
        }
    }

    /// Make sure the latest text of `uri` gets analysed: start the document's analysis task
    /// unless one runs already (it takes the latest text when it finishes the one in hand).
    /// So a storm of edits costs one analysis at a time, each of the latest text, however
    /// many edits queue up meanwhile.
    fn analyse(&self, uri: Uri) {
        {
            let mut state = self.state();
            let Some(open) = state.documents.get_mut(&uri) else {
                return;
            };
            if open.busy {
                return;
            }
            open.busy = true;
        }
        let this = self.clone();
        tokio::spawn(async move { this.analysis_task(uri).await });
    }

    async fn analysis_task(&self, uri: Uri) {
        loop {
            let job = {
                let mut state = self.state();
                let (limit, settings) = (state.model.max_document_bytes, state.model);
                let Some(open) = state.documents.get_mut(&uri) else {
                    return; // closed meanwhile
                };
                let done = open
                    .analysed
                    .as_ref()
                    .is_some_and(|d| d.version == open.version);
                if done || open.out_of_sync.is_some() {
                    open.busy = false;
                    return;
                }
                // The analysis of an older text leaves the store now (every request waits
                // for the latest anyway): it becomes the base of the next one, which
                // re-reads only what the edits changed, and memory stays that of about one
                // analysed document.
                let previous = open.analysed.take();
                let job = (
                    open.text.clone(),
                    open.kind,
                    open.version,
                    open.path.clone(),
                );
                (job, limit, previous, settings, open.latest.clone())
            };
            let ((text, kind, version, path), limit, previous, settings, latest) = job;
            let analysis = tokio::task::spawn_blocking(move || {
                // The previous analysis is reused in place once nothing else holds it: a
                // request being answered on it, or its diagnostics being made, let go of it
                // within milliseconds. Should one not, what it parsed is copied.
                let previous = previous.map(take_when_free);
                // A large text, new or previous: what its analysis left free in this
                // worker's arena (the profile read, the unescaped copy, the grown vectors)
                // goes back to the system once it is in place, before the OrcaSlicer lint
                // allocates in another thread's arena beside it.
                let large = previous.as_ref().is_some_and(|d| d.text.len() > LARGE)
                    || text.as_ref().is_some_and(|t| t.len() > LARGE);
                let doc = guard(|| match text {
                    Some(text) if text.len() <= limit => {
                        // The text is shared with the store, not copied.
                        match previous {
                            Some(previous) => {
                                Document::update(previous, text, kind, version, path.as_deref())
                            }
                            None => Document::new(text, kind, version, path.as_deref()),
                        }
                    }
                    Some(text) => Document::too_large(text.len(), limit, kind, version),
                    None => Document::too_large(0, limit, kind, version),
                });
                doc.inspect(|doc| {
                    // Ready for the hovers to come, unless a newer text is waiting.
                    if latest.load(Ordering::Relaxed) != version {
                        return;
                    }
                    for index in 0..doc.regions.len() {
                        let _ = guard(|| doc.preview(index, &settings));
                    }
                })
                .map(|doc| (doc, large))
            })
            .await;
            let (doc, large) = match analysis {
                Ok(Some((doc, large))) => (Arc::new(doc), large),
                // A panic (a bug, reported on stderr): this version shows no templates;
                // the next edit tries again.
                _ => (
                    Arc::new(Document::new(String::new(), kind, version, None)),
                    false,
                ),
            };
            let latest = {
                let mut state = self.state();
                let Some(open) = state.documents.get_mut(&uri) else {
                    return;
                };
                let latest = open.version == version;
                if open.analysed.as_ref().is_none_or(|d| d.version <= version) {
                    // The previous analysis goes: memory is bounded by the current text.
                    open.analysed = Some(doc.clone());
                }
                if let Some((len, _)) = doc.too_large
                    && latest
                    && len > 0
                {
                    open.text = None; // not kept: a pasted log file costs nothing
                }
                latest
            };
            self.analysed.send_modify(|n| *n += 1);
            drop(doc);
            if large {
                // What was left of the previous analysis (freed on a worker thread) handed
                // back to the system, or each worker's arena would keep a document's worth;
                // after the new analysis is in place, so no hover waits for it, and before
                // the diagnostics' lint starts, so its memory comes from what was freed.
                let _ = tokio::task::spawn_blocking(crate::memory::release).await;
            }
            if latest {
                self.schedule_publish(uri.clone());
            }
        }
    }

    /// An edit could not be applied: say so in the log and on the document, and wait for
    /// the whole text (see `crate::sync`).
    async fn out_of_sync(&self, uri: Uri, why: String) {
        let version = {
            let mut state = self.state();
            let Some(open) = state.documents.get_mut(&uri) else {
                return;
            };
            open.out_of_sync = Some(why.clone());
            open.version
        };
        self.analysed.send_modify(|n| *n += 1);
        let message = format!(
            "rotlang: an edit to {} could not be applied ({why}); the server waits for the \
             whole text: edit or save the file, or close and reopen it",
            uri.as_str()
        );
        self.client.log_message(MessageType::ERROR, &message).await;
        let diagnostic = Diagnostic {
            range: Range::default(),
            severity: Some(DiagnosticSeverity::ERROR),
            code: Some(NumberOrString::String(sync::OUT_OF_SYNC.into())),
            source: Some(diagnostics::SOURCE.into()),
            message: format!(
                "rotlang is out of step with this document: an edit could not be applied \
                 ({why}). Edit or save the file, or close and reopen it."
            ),
            ..Diagnostic::default()
        };
        self.client
            .publish_diagnostics(uri, vec![diagnostic], Some(version))
            .await;
    }

    /// `rotlang-lsp/invalidChange`: a `didChange` the server could not read, turned into
    /// this by the framing guard (`crate::transport`), which cannot reach the documents.
    async fn invalid_change(&self, params: InvalidChange) {
        let Some(uri) = params.uri else {
            self.client
                .log_message(
                    MessageType::ERROR,
                    format!(
                        "rotlang: a didChange without a document was ignored: {}",
                        params.reason
                    ),
                )
                .await;
            return;
        };
        if self.state().documents.contains_key(&uri) {
            self.out_of_sync(uri, params.reason).await;
        }
    }
}

/// The document of `doc` once this is its last handle, waiting up to `TAKE_WAIT` for
/// the others to go; else a copy of what an update needs (`Document::copy_for_update`).
fn take_when_free(mut doc: Arc<Document>) -> Document {
    let started = std::time::Instant::now();
    loop {
        match Arc::try_unwrap(doc) {
            Ok(doc) => return doc,
            Err(shared) if started.elapsed() < TAKE_WAIT => {
                doc = shared;
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
            Err(shared) => return shared.copy_for_update(),
        }
    }
}

/// How long an analysis waits for others to let go of the previous one (a copy of a 4 MB
/// template's spans is a few MB: copying is cheap too).
const TAKE_WAIT: std::time::Duration = std::time::Duration::from_millis(50);

/// Closing a document this large (bytes) hands its memory back to the system.
const LARGE: usize = 1 << 20;

/// A `didChange` the framing guard could not read, forwarded under this name (the
/// transport's, which forwards it).
pub use crate::transport::INVALID_CHANGE;

/// The parameters of `rotlang-lsp/invalidChange` (see `crate::transport`).
#[derive(serde::Deserialize)]
struct InvalidChange {
    uri: Option<Uri>,
    reason: String,
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
        let path = d.uri.to_file_path().map(|p| p.into_owned());
        // A reopened document starts afresh (in sync, with nothing analysed).
        self.state()
            .documents
            .insert(d.uri.clone(), Open::new(kind, d.version, d.text, path));
        self.analyse(d.uri);
    }

    async fn did_change(&self, params: DidChangeTextDocumentParams) {
        let uri = params.text_document.uri;
        // Applying the edits is all that happens here: the analysis runs in its own task,
        // on the latest text only, so edits never queue up behind analyses.
        let (text, encoding, dropped) = {
            let state = self.state();
            let Some(open) = state.documents.get(&uri) else {
                return; // a change to a document never opened: nothing to apply it to
            };
            let text = open.text.clone().filter(|_| open.out_of_sync.is_none());
            // Over the size limit the text is not kept: a ranged edit has nothing to apply to.
            let dropped = open.text.is_none() && open.out_of_sync.is_none();
            (text, state.encoding, dropped)
        };
        let ranged_first = params
            .content_changes
            .first()
            .is_some_and(|c| c.range.is_some());
        match sync::apply(
            text.as_deref().map(String::as_str),
            params.content_changes,
            encoding,
        ) {
            Applied::Text(text) => {
                {
                    let mut state = self.state();
                    let Some(open) = state.documents.get_mut(&uri) else {
                        return;
                    };
                    open.text = Some(Arc::new(text));
                    open.version = params.text_document.version;
                    open.latest.store(open.version, Ordering::Relaxed);
                    open.out_of_sync = None;
                }
                self.analysed.send_modify(|n| *n += 1);
                self.analyse(uri);
            }
            Applied::Rejected(why) => self.out_of_sync(uri, why).await,
            Applied::Nothing if dropped && ranged_first => {
                let why = "the document was over the size limit, so its text was not kept";
                self.out_of_sync(uri, why.into()).await;
            }
            Applied::Nothing => {}
        }
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        let uri = params.text_document.uri;
        let closed = self.state().documents.remove(&uri);
        self.analysed.send_modify(|n| *n += 1);
        if closed
            .as_ref()
            .is_some_and(|c| c.text.as_ref().is_some_and(|t| t.len() > LARGE))
        {
            // Its analysis was made on a worker thread, whose arena keeps the memory.
            drop(closed);
            crate::memory::release();
        }
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
        self.apply_settings(section).await;
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        let p = params.text_document_position_params;
        let plain = self.state().plain_hover;
        let Some((doc, encoding, model)) = self.current(&p.text_document.uri).await else {
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
        let Some((doc, encoding, _)) = self.current(&p.text_document.uri).await else {
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
        let Some((doc, encoding, _)) = self.current(&params.text_document.uri).await else {
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
        let Some((doc, encoding, settings)) = self.current(&params.text_document.uri).await else {
            return Ok(None);
        };
        let keep_orcaslicer = settings.compat.applies_to(doc.kind);
        guard(|| {
            formatting::formatting(&doc, &Positions::new(&doc.text, encoding), keep_orcaslicer)
        })
        .ok_or_else(internal)
    }

    async fn inlay_hint(&self, params: InlayHintParams) -> Result<Option<Vec<InlayHint>>> {
        let Some((doc, encoding, model)) = self.current(&params.text_document.uri).await else {
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
        let Some((doc, encoding, settings)) = self.current(&uri).await else {
            return Ok(None);
        };
        guard(|| {
            let pos = Positions::new(&doc.text, encoding);
            let range = pos.span(params.range)?;
            // The compat findings published with the diagnostics (cached with them).
            let found = crate::compat::cached(&doc, &settings);
            Some(code_actions::code_actions(&doc, &uri, range, &pos, &found))
        })
        .ok_or_else(internal)
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        let Some((doc, encoding, model)) = self.current(&params.text_document.uri).await else {
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
        let (service, socket) = LspService::build(Backend::new)
            .custom_method(INVALID_CHANGE, Backend::invalid_change)
            .finish();
        Server::new(input, output, socket).serve(service).await;
    })
    .await;
}
