#!/bin/bash
# Ctrl+S saves the running scene as JSON (every key of `slime settings`); after the file is edited,
# Ctrl+O loads it and the change is applied; a broken file leaves the running scene as it was and
# the panel says why. The saved scene is one `slime snapshot --scene` accepts.
source "$(dirname "$0")/viewer_lib.sh"
cd "$OUT" || fail "no $OUT"
start_viewer --size 730x360 --set sim.paused=true --set slime.stiffness=123
sleep 2
screenshot 1
xdotool key --window "$WINDOW" ctrl+s
for _ in $(seq 1 50); do [ -s slime-scene.json ] && break; sleep 0.1; done
[ -s slime-scene.json ] || fail "Ctrl+S wrote no slime-scene.json"
for key in $("$SLIME" settings --json | jq -r '.[].key'); do
  jq -e "getpath(\"$key\" | split(\".\")) != null" slime-scene.json > /dev/null || fail "the saved scene lacks $key"
done
[ "$(jq '.slime.stiffness' slime-scene.json)" = "123" ] || fail "the saved stiffness is $(jq '.slime.stiffness' slime-scene.json), not 123"
"$SLIME" snapshot --scene slime-scene.json --settle 0 --size 64x48 -o from-saved.png > /dev/null ||
  fail "slime snapshot does not accept the saved scene"

jq '.slime.color = [0.9, 0.1, 0.1] | .slime.transmission = 0.2 | .camera.fov = 60' slime-scene.json > edited.json
mv edited.json slime-scene.json
xdotool key --window "$WINDOW" ctrl+o
sleep 2
screenshot 2
changed=$(differing_pixels shot-1.png shot-2.png)
[ "$changed" -gt 20000 ] || fail "loading the edited scene changed only $changed pixels"

echo '{"slime": {"level": 12}}' > slime-scene.json  # valid JSON, invalid scene
xdotool key --window "$WINDOW" ctrl+o
sleep 1
screenshot 3
quit_viewer

[ "$(report '.settings.slime.color[0]')" = "0.9" ] || fail "the loaded colour was not applied: $(report '.settings.slime.color')"
[ "$(report '.settings.camera.fov')" = "60" ] || fail "the loaded fov was not applied: $(report '.settings.camera.fov')"
[ "$(report '.settings.slime.level')" = "4" ] || fail "the failed load changed the scene (level $(report '.settings.slime.level'))"
message=$(report '.file_message')
echo "$message" | grep -q "Not loaded.*slime.level" || fail "the failed load does not say why: '$message'"
echo "PASS: saved every key, loaded the edit ($changed pixels changed), refused level 12: $message"
