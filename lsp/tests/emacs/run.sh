#!/usr/bin/env bash
# End-to-end run with a real editor: Emacs (Debian's emacs-nox 28) with eglot (Debian's
# elpa-eglot 1.9) loads editors/emacs/rotlang.el, the documented set-up, and drives
# rotlang-lsp through it (e2e.el): diagnostics, the fix clearing them, hover, completion,
# and a JSON profile.
#
# Usage: run.sh PATH/TO/rotlang-lsp RESULT.json
# Installs the packages through scripts/ensure; exits 77 ("skipped") when it cannot.
set -euo pipefail

server=${1:?usage: run.sh SERVER RESULT.json}
out=${2:?usage: run.sh SERVER RESULT.json}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)

status=0
"$root/scripts/ensure" apt emacs-nox elpa-eglot || status=$?
if [ "$status" -eq 77 ]; then
    echo "SKIPPED: emacs-nox and elpa-eglot are not installed and cannot be (see above)"
    exit 77
elif [ "$status" -ne 0 ]; then
    exit "$status"
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/bin" "$work/home"
ln -s "$(cd "$(dirname "$server")" && pwd)/$(basename "$server")" "$work/bin/rotlang-lsp"

# --batch -Q: no init files, not even Debian's site start-up, so the packages' directories
# are put on the load path by hand (Debian's elpa-* packages: eglot and the newer
# project/xref/seq it needs). HOME is a scratch directory: nothing of the user's is read.
load_path=()
for d in /usr/share/emacs/site-lisp/elpa/*/; do load_path+=(-L "$d"); done
HOME="$work/home" PATH="$work/bin:$PATH" \
    ROTLANG_SETUP="$root/editors/emacs/rotlang.el" ROTLANG_OUT="$out" ROTLANG_DIR="$work" \
    timeout 120 emacs --batch -Q "${load_path[@]}" -l "$here/e2e.el" </dev/null
