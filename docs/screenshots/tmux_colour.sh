#!/usr/bin/env bash
# Screenshots of the game inside tmux, as a player who logged in over SSH (no COLORTERM) and
# started tmux meets it: TERM is tmux's `tmux-256color`, so the game picks 256 colours. Each size
# and colour level is captured from tmux's own screen (`capture-pane -e`), then put side by side
# with the same view in truecolor (COLORTERM=truecolor) by examples/screen_sheet.rs.
#
#   docs/screenshots/tmux_colour.sh [target/release/halfcast] [OUT_DIR]
#
# Writes OUT_DIR/tmux-80x24.png (truecolor | 256) and OUT_DIR/tmux-160x48.png
# (truecolor | 256 | 16) of the start view, and OUT_DIR/tmux-wood-120x40.png (truecolor | 256 |
# 16) facing the wood door and the barrel, the hardest colours for the palette, and
# OUT_DIR/tmux-heights-120x40.png (truecolor | 256) of maps/heights.cub's warm floor. Needs tmux;
# not part of CI.
set -euo pipefail
bin=$(realpath "${1:-target/release/halfcast}")
out=${2:-docs/screenshots}
tmp=$(mktemp -d)
sock="halfcast-shots-$$"
trap 'tmux -L "$sock" kill-server 2>/dev/null || true; rm -rf "$tmp"' EXIT

printf 'set -g status off\nset -g default-terminal tmux-256color\n' >"$tmp/tmux.conf"
# A session that outlives every capture, so killing a capture's session never stops the server
# while the next one starts (tmux then says "server exited unexpectedly").
tmux -L "$sock" -f "$tmp/tmux.conf" new-session -d -s keep "sleep 600"

# One capture: the game at COLSxROWS in a fresh tmux window, COLORTERM unset unless asked for,
# after it has settled.
capture() {
  local size=$1 colorterm=$2 file=$3
  shift 3
  local cols=${size%x*} rows=${size#*x}
  tmux -L "$sock" -f "$tmp/tmux.conf" new-session -d -s shot -x "$cols" -y "$rows" \
    "env -u COLORTERM ${colorterm:+COLORTERM=$colorterm} $bin --seed 1 $*; sleep 30"
  sleep 3
  tmux -L "$sock" capture-pane -e -p -t shot >"$file"
  tmux -L "$sock" kill-session -t shot
}

capture 80x24 truecolor "$tmp/80-true.ans"
capture 80x24 "" "$tmp/80-256.ans"
capture 160x48 truecolor "$tmp/160-true.ans"
capture 160x48 "" "$tmp/160-256.ans"
capture 160x48 "" "$tmp/160-16.ans" --colors 16
wood=(--pos 12.5,9.5 --angle 160)
capture 120x40 truecolor "$tmp/wood-true.ans" "${wood[@]}"
capture 120x40 "" "$tmp/wood-256.ans" "${wood[@]}"
capture 120x40 "" "$tmp/wood-16.ans" "${wood[@]}" --colors 16
heights=(maps/heights.cub --pos 7.49,6.70 --angle 161.8)
capture 120x40 truecolor "$tmp/heights-true.ans" "${heights[@]}"
capture 120x40 "" "$tmp/heights-256.ans" "${heights[@]}"

sheet() { cargo run -q --release --features vt100 --example screen_sheet -- "$@"; }
sheet "$out/tmux-80x24.png" 3 "$tmp/80-true.ans" "$tmp/80-256.ans"
sheet "$out/tmux-160x48.png" 2 "$tmp/160-true.ans" "$tmp/160-256.ans" "$tmp/160-16.ans"
sheet "$out/tmux-wood-120x40.png" 2 "$tmp/wood-true.ans" "$tmp/wood-256.ans" "$tmp/wood-16.ans"
sheet "$out/tmux-heights-120x40.png" 2 "$tmp/heights-true.ans" "$tmp/heights-256.ans"
