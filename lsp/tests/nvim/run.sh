#!/usr/bin/env bash
# End-to-end run with a real editor: headless Neovim starts rotlang-lsp through
# `vim.lsp.start_client` (the 0.7 API), opens a bad .rot file, waits for the
# diagnostic, fixes the text, sees the diagnostics cleared, and hovers (e2e.lua).
#
# Usage: run.sh PATH/TO/rotlang-lsp RESULT.json [INIT.lua]
# With INIT.lua (the README's snippet), Neovim starts with it as the user's init file and
# rotlang-lsp on PATH, and readme.lua opens one file of each kind.
# Installs Debian's `neovim` through scripts/ensure when `nvim` is missing; exits 77
# ("skipped") with a message saying why when it cannot.
set -euo pipefail

server=${1:?usage: run.sh SERVER RESULT.json}
out=${2:?usage: run.sh SERVER RESULT.json}
here=$(cd "$(dirname "$0")" && pwd)

if ! command -v nvim >/dev/null 2>&1; then
    # The shared, locked installer: tests run in parallel and apt must not.
    status=0
    "$here/../../../scripts/ensure" apt neovim || status=$?
    if [ "$status" -eq 77 ]; then
        echo "SKIPPED: nvim is not installed and cannot be (see above)"
        exit 77
    elif [ "$status" -ne 0 ]; then
        exit "$status"
    fi
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if [ -n "${3:-}" ]; then
    mkdir -p "$work/bin"
    ln -s "$(cd "$(dirname "$server")" && pwd)/$(basename "$server")" "$work/bin/rotlang-lsp"
    # -u INIT: the snippet is the whole configuration (filetype detection on, as for a
    # user); -i NONE -n: no shada, no swap.
    PATH="$work/bin:$PATH" ROTLANG_OUT="$out" ROTLANG_DIR="$work" \
        timeout 120 nvim --headless -u "$3" -i NONE -n -c "luafile $here/readme.lua" </dev/null
    exit
fi

# -u NONE -i NONE -n: no user config, no shada, no swap: the run sees only e2e.lua.
# The timeout is a last resort: e2e.lua bounds each wait itself and always quits.
ROTLANG_LSP="$server" ROTLANG_OUT="$out" ROTLANG_DIR="$work" \
    timeout 120 nvim --headless -u NONE -i NONE -n -c "luafile $here/e2e.lua" </dev/null
