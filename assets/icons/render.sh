#!/usr/bin/env sh
# Renders the icon's PNGs at the sizes the freedesktop icon theme asks for
# (hicolor: 16 … 512), from servo-studio.svg. Needs rsvg-convert (librsvg2-bin).
set -eu
cd "$(dirname "$0")"
for size in 16 22 24 32 48 64 128 256 512; do
    rsvg-convert --width "$size" --height "$size" servo-studio.svg --output "servo-studio-$size.png"
done
