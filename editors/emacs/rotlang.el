;;; rotlang.el --- rot-mode and eglot set-up for rotlang-lsp  -*- lexical-binding: t; -*-

;; Infill rotation templates (.rot files) and the templates inside OrcaSlicer profiles
;; (JSON presets and .ini exports), checked by `rotlang-lsp' through eglot.  Written for Emacs 28 with eglot 1.9
;; (Debian 12's `emacs' + `elpa-eglot'); newer Emacs and eglot work the same way.
;;
;; Load it from your init file:
;;   (load "/path/to/rotlang/editors/emacs/rotlang.el")
;; and make sure `rotlang-lsp' is on `exec-path' (cargo install puts it in ~/.cargo/bin).

(require 'eglot)
(require 'js)
(require 'conf-mode)

(defvar rot-mode-syntax-table
  (let ((table (make-syntax-table)))
    ;; Every character of an instruction is part of one symbol, so that eglot's
    ;; completion (which filters by the symbol at point) sees `+30' in `0, +30', the text
    ;; the server's completion items replace.  Separators are `,' and whitespace.
    (dolist (c (string-to-list "+-*!/$~^|#%'\".:<>=_&?@;`"))
      (modify-syntax-entry c "_" table))
    (modify-syntax-entry ?, "." table)
    (modify-syntax-entry ?\s " " table)
    (modify-syntax-entry ?\t " " table)
    (modify-syntax-entry ?\n " " table)
    (modify-syntax-entry ?\r " " table)
    table)
  "Syntax table for `rot-mode': instructions are symbols, no strings, no comments.")

(defvar rot-mode-font-lock-keywords
  '(("\\(?:^\\|[ ,\t]\\)\\([-+]\\)[0-9.]" 1 font-lock-builtin-face)
    ("[0-9.]+\\(?::[0-9.]+\\|%\\)?" . font-lock-constant-face)
    ("[DSOMR]" . font-lock-type-face)
    ("[/NnZz$LlUuQq~^|#]" . font-lock-keyword-face)
    ("mm\\|cm\\|m\\|['\"%]" . font-lock-variable-name-face)
    ("[*!]" . font-lock-warning-face))
  "Highlighting until the server's semantic tokens are shown (eglot 1.9 has none).")

;;;###autoload
(define-derived-mode rot-mode prog-mode "Rot"
  "Major mode for infill rotation templates (OrcaSlicer's rotate templates)."
  :syntax-table rot-mode-syntax-table
  (setq-local comment-start nil)
  (setq-local font-lock-defaults '(rot-mode-font-lock-keywords t)))

;;;###autoload
(add-to-list 'auto-mode-alist '("\\.rot\\'" . rot-mode))

;;;###autoload
(define-derived-mode rotlang-json-mode js-mode "JSON"
  "JSON slicer profiles whose rotate templates rotlang-lsp checks.
A mode of its own, so that JavaScript buffers keep their own language server."
  ;; As in `rot-mode': an instruction inside a template string is one symbol, for eglot's
  ;; completion.  Outside strings JSON has only numbers and punctuation, so nothing else
  ;; changes; `/' and `*' keep their comment flags for .jsonc comments.
  (dolist (c (string-to-list "+-!$~^|#%:.'"))
    (modify-syntax-entry c "_"))
  (modify-syntax-entry ?/ "_ 124b")
  (modify-syntax-entry ?* "_ 23"))

;;;###autoload
(define-derived-mode rotlang-ini-mode conf-windows-mode "Conf[rotlang]"
  "OrcaSlicer `.ini' exports (`key = value', `;' comments), whose rotate templates
rotlang-lsp checks.  A mode of its own, so that other .ini files stay plain `conf-mode'.")

(defconst rotlang--template-key
  "\"?\\(?:sparse\\|solid\\)_infill_rotate_template\"?[ \t]*[:=]"
  "A rotate template key, as a JSON member or an .ini line.")

(defconst rotlang--orca-folder
  "/\\(?:OrcaSlicer\\|orca-slicer\\)/\\|/resources/profiles/"
  "OrcaSlicer's folders: its configuration (user/, system/) and its sources' profiles.")

(defun rotlang--profile-p (extension)
  "Whether the file being visited, ending in EXTENSION, is an OrcaSlicer profile.
By folder (OrcaSlicer's own) or by content (a rotate template key in the first 256 KB);
called by `set-auto-mode' with the file's text in the buffer."
  (let ((file (or buffer-file-name "")))
    (and (string-match-p extension file)
         (or (string-match-p rotlang--orca-folder file)
             (save-excursion
               (goto-char (point-min))
               (re-search-forward rotlang--template-key
                                  (min (point-max) (+ (point-min) 262144)) t))))))

;; OrcaSlicer profiles only: a .json/.jsonc file with a template key or in OrcaSlicer's
;; folders, and an .ini export with one.  Other JSON files (package.json, tsconfig.json)
;; keep their usual mode and server.
;;;###autoload
(defun rotlang-json-profile-p ()
  "Whether the file being visited is an OrcaSlicer JSON (or jsonc) preset."
  (rotlang--profile-p "\\.jsonc?\\'"))
;;;###autoload
(defun rotlang-ini-profile-p ()
  "Whether the file being visited is an OrcaSlicer .ini export."
  (rotlang--profile-p "\\.ini\\'"))
;;;###autoload
(add-to-list 'magic-mode-alist '(rotlang-json-profile-p . rotlang-json-mode))
;;;###autoload
(add-to-list 'magic-mode-alist '(rotlang-ini-profile-p . rotlang-ini-mode))

;; Three entries, so .rot files, JSON profiles and .ini exports each get their own server
;; and language id (the server also tells them apart by the file extension).
(add-to-list 'eglot-server-programs
             '((rot-mode :language-id "rotlang") . ("rotlang-lsp")))
(add-to-list 'eglot-server-programs
             '((rotlang-json-mode :language-id "json") . ("rotlang-lsp")))
(add-to-list 'eglot-server-programs
             '((rotlang-ini-mode :language-id "ini") . ("rotlang-lsp")))

(add-hook 'rot-mode-hook #'eglot-ensure)
(add-hook 'rotlang-json-mode-hook #'eglot-ensure)
(add-hook 'rotlang-ini-mode-hook #'eglot-ensure)

;; The model that hovers are computed for is a setting (see lsp/README.md): put it in
;; `eglot-workspace-configuration', in your init file
;;   (setq-default eglot-workspace-configuration
;;                 '(:rotlang (:layers 250 :layerHeight 0.16)))
;; or per project in .dir-locals.el:
;;   ((nil . ((eglot-workspace-configuration
;;             . (:rotlang (:layers 250 :layerHeight 0.16))))))

(provide 'rotlang)
;;; rotlang.el ends here
