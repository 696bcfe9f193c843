#!/usr/bin/env bash
# The OpenArena tests with more game data installed than they were checked against
# (docs/real-frames.md, "Game data"): Debian's full `openarena` 0.8.8 puts archives beside
# openarena-081-maps' pak1-maps.pk3 and openarena-081-textures' pak4-textures.pk3 that override
# levels and textures (Quake III's search order: the later archive wins). This builds such a game
# directory (links to the two installed archives, and pak6-patch088.pk3 that replaces
# maps/aggressor.bsp by another level, replaces the texture textures/e7/e7walldesign01 and adds a
# level), checks that the tool reads the added archive, and runs the OpenArena tests with it as
# $TFU_OPENARENA_DIR: they read exactly the checked archives (testbench/q3_test_data.hpp,
# CheckedGameData) and pass. Exit 77 (skipped) when the game data is not installed.
#
#   testbench/game_data_overridden_test.sh BUILD/bin/tfu BUILD/bin/tfu_tests [WORK]
set -euo pipefail
tfu=$(realpath "$1")
tests=$(realpath "$2")
work=${3:-$(mktemp -d /tmp/tfu-game-data.XXXXXX)}
installed=${TFU_OPENARENA_DIR:-/usr/share/games/openarena/baseoa}
for pk3 in pak1-maps.pk3 pak4-textures.pk3; do
  [[ -f $installed/$pk3 ]] || { echo "game_data_overridden_test: $installed/$pk3 not installed: skipped"; exit 77; }
done
rm -rf "$work" && mkdir -p "$work/baseoa"
game=$(realpath "$work/baseoa")
ln -s "$(realpath "$installed/pak1-maps.pk3")" "$(realpath "$installed/pak4-textures.pk3")" "$game/"
/usr/bin/python3 - "$game" <<'PY'
import sys, zipfile
game = sys.argv[1]
maps = zipfile.ZipFile(f"{game}/pak1-maps.pk3")
textures = zipfile.ZipFile(f"{game}/pak4-textures.pk3")
other = next(n for n in sorted(maps.namelist()) if n.lower().endswith(".bsp") and "aggressor" not in n.lower())
jpeg = next(n for n in sorted(textures.namelist()) if n.lower().endswith(".jpg") and "e7walldesign01" not in n.lower())
with zipfile.ZipFile(f"{game}/pak6-patch088.pk3", "w") as out:
    out.writestr("maps/aggressor.bsp", maps.read(other))
    out.writestr("maps/zz_added_level.bsp", maps.read(other))
    out.writestr("textures/e7/e7walldesign01.jpg", textures.read(jpeg))
PY
export TFU_OPENARENA_DIR=$game
"$tfu" render --list | grep -q '^oa:zz_added_level  pak6-patch088.pk3:maps/zz_added_level.bsp$' ||
  { echo "game_data_overridden_test: FAIL: tfu render --list does not read the added archive"; exit 1; }
"$tests" --gtest_filter='OpenArena.*' --gtest_brief=1
echo "game_data_overridden_test: the OpenArena tests pass with an overriding archive installed"
