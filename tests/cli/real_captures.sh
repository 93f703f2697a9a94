# Sourced by the command-line tests on the shared real data set (five chessboard poses under
# OpenCV's Gray-code sequence: 1024 x 768 codes of 2 x 2 pixels, a 2048 x 1536 projector; the
# authors' OpenCV XML calibration in millimetres). The caller sets `binpick`, `work` and fail().
#   require_real_captures DIR   sets `data`, or exits 77 (skipped) where the data set is missing
#   import_real_capture I OUT   imports capture_I as it comes; its output in $work/import.log
require_real_captures() {
  data="$1/kamino410-procam-calibration"
  if [ ! -f "$data/calibration_result.xml" ]; then
    echo "SKIP: no real captures at $data (the shared real data set)"
    exit 77
  fi
}

import_real_capture() {
  "$binpick" import-capture --images "$data/capture_$1" --preset opencv-graycode --projector 2048x1536 \
    --code-step 2 --opencv-calib "$data/calibration_result.xml" --out "$2" >"$work/import.log" 2>&1 ||
    fail "import of capture_$1 exited $?: $(cat "$work/import.log")"
}
