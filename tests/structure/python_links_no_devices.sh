#!/usr/bin/env bash
# The Python module links no device, simulator or Qt library (docs/architecture.md): it reads
# datasets (keyturn_dataset) and learns (keyturn_learning) over core, nothing more.
# Two places a regression shows: the module's link line (static libraries such as keyturn_rig or
# keyturn_drivers are folded in there, and the linker's --as-needed hides their shared libraries
# from the binary when no code of theirs is used) and the shared libraries the module needs.
# Usage: python_links_no_devices.sh BUILD_DIR GENERATOR MAKE_PROGRAM MODULE
set -euo pipefail
build=$1 generator=$2 make_program=$3 module=$4

# What the build links the module with: the last command ninja runs for it, or make's link.txt.
if [[ $generator == Ninja* ]]; then
  link=$("$make_program" -C "$build" -t commands keyturn_python | tail -n 1)
else
  link=$(cat "$build/ui/python/CMakeFiles/keyturn_python.dir/link.txt")
fi
[[ $link == *"$(basename "$module")"* ]] || { echo "FAIL: no link command for $module found"; exit 1; }
needed=$(readelf -d "$module" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
[[ -n $needed ]] || { echo "FAIL: readelf found no NEEDED entry in $module"; exit 1; }

forbidden='keyturn_rig|keyturn_drivers|keyturn_sim|mesasr|keyturn_studio_ui|keyturn_ui\b|libusb|usb-1\.0|modbus|embree|Qt5|libQt'
status=0
if found=$(tr ' ' '\n' <<<"$link" | grep -E "$forbidden" | sort -u) && [[ -n $found ]]; then
  echo "FAIL: the Python module is linked with device, simulator or Qt libraries:"
  sed 's/^/  /' <<<"$found"
  status=1
fi
if found=$(grep -E "$forbidden" <<<"$needed") && [[ -n $found ]]; then
  echo "FAIL: the Python module needs device, simulator or Qt libraries at run time:"
  sed 's/^/  /' <<<"$found"
  status=1
fi
if [[ $status == 0 ]]; then
  echo "OK: $(basename "$module") links $(tr ' ' '\n' <<<"$link" | grep -oE 'libkeyturn_[a-z_]+\.a' | sort -u | tr '\n' ' ')and needs $(wc -w <<<"$needed") shared libraries, none of a device, the simulator or Qt"
fi
exit $status
