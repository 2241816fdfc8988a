;;; e2e.el --- drive eglot against rotlang-lsp, headless  -*- lexical-binding: t; -*-

;; Run by run.sh: ROTLANG_SETUP (editors/emacs/rotlang.el), ROTLANG_OUT (result JSON),
;; ROTLANG_DIR (scratch directory).  rotlang-lsp is on PATH.  Every wait is bounded and
;; the result is written whatever happens.

(require 'json)
(require 'cl-lib)

(defvar e2e-result nil "Alist written to ROTLANG_OUT.")
(defun e2e-put (key value) (push (cons key value) e2e-result))

(defun e2e-wait (pred &optional seconds)
  "Wait until PRED returns non-nil (at most SECONDS, 15 by default)."
  (let ((deadline (+ (float-time) (or seconds 15))) value)
    (while (and (not (setq value (funcall pred))) (< (float-time) deadline))
      (accept-process-output nil 0.05))
    value))

(defun e2e-diagnostics ()
  "The buffer's flymake diagnostics as alists with zero-based columns."
  (mapcar (lambda (d)
            (list (cons 'message (flymake-diagnostic-text d))
                  (cons 'line (1- (line-number-at-pos (flymake-diagnostic-beg d))))
                  (cons 'col (save-excursion (goto-char (flymake-diagnostic-beg d))
                                             (current-column)))
                  (cons 'end_col (save-excursion (goto-char (flymake-diagnostic-end d))
                                                 (current-column)))
                  (cons 'type (symbol-name (flymake-diagnostic-type d)))))
          (flymake-diagnostics)))

(defun e2e-open (name text)
  "Visit NAME in the scratch directory holding TEXT, with eglot connected."
  (let ((path (expand-file-name name (getenv "ROTLANG_DIR"))))
    (with-temp-file path (insert text))
    (find-file path)
    ;; eglot-ensure connects from `post-command-hook'; there are no commands here.
    (unless (eglot-current-server) (apply #'eglot (eglot--guess-contact)))
    (e2e-wait #'eglot-current-server)
    (current-buffer)))

(defun e2e-change (text)
  "Replace the buffer's text and tell the server now (eglot would on an idle timer)."
  (erase-buffer)
  (insert text)
  (eglot--signal-textDocument/didChange))

(defun e2e-run ()
  (load (getenv "ROTLANG_SETUP"))
  ;; The documented settings: a 40-layer model of 0.3 mm layers.
  (setq-default eglot-workspace-configuration
                '(:rotlang (:layers 40 :layerHeight 0.3)))
  (setq eglot-sync-connect 10)

  ;; 1. A bad .rot file: the error at the X, with the message alone.
  (e2e-open "bad.rot" "0, +30X5, +22.5/50%")
  (e2e-put 'mode (symbol-name major-mode))
  (e2e-put 'connected (and (eglot-current-server) t))
  (flymake-start)
  (e2e-wait (lambda () (flymake-diagnostics)))
  (e2e-put 'diagnostics (vconcat (e2e-diagnostics)))

  ;; 2. Fix it: the diagnostics clear.
  (e2e-change "0, +30/5, +22.5/50%")
  (e2e-put 'cleared (and (e2e-wait (lambda () (null (flymake-diagnostics)))) t))

  ;; 3. Hover on `+22.5/50%', as eldoc would show it.
  (goto-char (+ (point-min) 13))
  (let ((hover (jsonrpc-request (eglot-current-server) :textDocument/hover
                                (eglot--TextDocumentPositionParams))))
    (e2e-put 'hover_kind (plist-get (plist-get hover :contents) :kind))
    (e2e-put 'hover (eglot--hover-info (plist-get hover :contents))))

  ;; 4. Completion after `+30': the joints are offered; choosing `/' inserts it.
  (e2e-change "0, +30")
  (goto-char (point-max))
  (let* ((capf (eglot-completion-at-point))
         (start (nth 0 capf)) (end (nth 1 capf)) (table (nth 2 capf))
         (exit (plist-get (nthcdr 3 capf) :exit-function))
         (candidates (all-completions (buffer-substring start (point)) table))
         (slash (cl-find "+30/" candidates :test #'string=)))
    (e2e-put 'candidates (vconcat (mapcar #'substring-no-properties candidates)))
    (when slash
      ;; What `completion-in-region' does: replace the field, then the exit function.
      (delete-region start end)
      (goto-char start)
      (insert slash)
      (funcall exit slash 'finished)
      (e2e-put 'completed (buffer-substring-no-properties (point-min) (point-max)))))

  ;; 5. A JSON profile: its own entry, read as a profile (one error, not ten).
  (e2e-open "process.json"
            "{\n  \"name\": \"0.20mm\",\n  \"sparse_infill_rotate_template\": \"0, +30X5\"\n}\n")
  (e2e-put 'json_mode (symbol-name major-mode))
  (flymake-start)
  (e2e-wait (lambda () (flymake-diagnostics)))
  (e2e-put 'json_diagnostics (vconcat (e2e-diagnostics)))

  ;; 6. Completion inside the profile's template string, after `+30/5c'.
  (e2e-change "{\n  \"sparse_infill_rotate_template\": \"0, +30/5c\"\n}\n")
  (goto-char (point-min))
  (search-forward "+30/5c")
  (let* ((capf (eglot-completion-at-point))
         (start (nth 0 capf)) (end (nth 1 capf)) (table (nth 2 capf))
         (exit (plist-get (nthcdr 3 capf) :exit-function))
         (candidates (all-completions (buffer-substring start (point)) table))
         (cm (cl-find "+30/5cm" candidates :test #'string=)))
    (e2e-put 'json_candidates (vconcat (mapcar #'substring-no-properties candidates)))
    (when cm
      (delete-region start end)
      (goto-char start)
      (insert cm)
      (funcall exit cm 'finished)
      (e2e-put 'json_completed (buffer-substring-no-properties (point-min) (point-max)))))

  ;; 7. An unrelated package.json: its usual mode, no rotlang server.
  (let ((path (expand-file-name "package.json" (getenv "ROTLANG_DIR"))))
    (with-temp-file path (insert "{\n  \"name\": \"app\",\n  \"version\": \"1.0.0\"\n}\n"))
    (find-file path)
    (e2e-put 'package_mode (symbol-name major-mode))
    (e2e-put 'package_server (if (eglot-current-server) t :json-false)))

  ;; 8. A preset recognised by its folder alone (OrcaSlicer's layout), no template key.
  (let ((dir (expand-file-name "OrcaSlicer/user/default/filament" (getenv "ROTLANG_DIR"))))
    (make-directory dir t)
    (let ((path (expand-file-name "PLA.json" dir)))
      (with-temp-file path (insert "{\n  \"name\": \"PLA\"\n}\n"))
      (find-file path)
      (e2e-put 'folder_mode (symbol-name major-mode))))

  ;; 9. An .ini export: its own mode, the server attached, the error at the X.
  (e2e-open "export.ini"
            "; generated by OrcaSlicer 2.3.0\nlayer_height = 0.2\nsparse_infill_rotate_template = 0, +30X5\n")
  (e2e-put 'ini_mode (symbol-name major-mode))
  (e2e-put 'ini_connected (and (eglot-current-server) t))
  (flymake-start)
  (e2e-wait (lambda () (flymake-diagnostics)))
  (e2e-put 'ini_diagnostics (vconcat (e2e-diagnostics)))
  (eglot-shutdown-all))

(let ((ok (condition-case err
              (progn (e2e-run) t)
            (error (e2e-put 'error (format "%S" err)) nil))))
  (e2e-put 'ok (if ok t :json-false))
  (with-temp-file (getenv "ROTLANG_OUT")
    (insert (json-encode e2e-result))))
(kill-emacs 0)
