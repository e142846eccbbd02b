#!/usr/bin/env bash
# The toolkit on a GPU machine with a LibTorch 2.x (issue 31), in one short run: builds the
# LibTorch programs against the LibTorch inside the machine's pip torch, checks that they link
# libtorch_cuda, and runs them with --device=cuda against --device=cpu on the same machine:
#   1. ts-rirgan-train, one step on CUDA (the smoke test of docs/recipe.md);
#   2. ts-rirgan-train at the paper's width 64 and batch 64 (the defaults otherwise): median
#      s/step on CUDA (20 steps) and on all CPU cores (3 steps), GPU memory and utilisation sampled;
#   3. gas-to-real, 512 RIRs through the CUDA-trained width-64 model, on CUDA and on the CPU:
#      RIRs/s and the largest difference between the two outputs;
#   4. asr-train one epoch on CUDA, resumed for a second on the CPU; asr-decode on both devices;
#   5. the torch-2.x compatibility test and the GAN network tests against the real LibTorch 2.x;
#   6. with the time left (up to 7.5 min in all), every other target, -k 0.
# Everything goes to OUT_DIR (default $OUT, else /tmp/cuda_check): summary.md (the figures),
# one log per step, ldd output, nvidia-smi samples.
#
# The machine is assumed to have: an NVIDIA GPU and driver, the CUDA toolkit (nvcc), python3 with
# torch (CUDA build) and numpy, cmake, ninja (or make), g++. The toolkit's other build
# dependencies come as Debian 12 packages in exp/cuda_check_debs (bench/gan/fetch_cuda_check_debs.sh
# downloads them elsewhere), unpacked here with dpkg -x (or ar+tar) into a prefix that CMake is
# pointed at (CMAKE_PREFIX_PATH) and that LD_LIBRARY_PATH covers (libsndfile and libsox are opened
# with dlopen when needed, which RUNPATH does not cover).
# TSRIR_CHECK_DEVICE=cpu rehearses the whole script on a machine without a GPU (every "cuda" run
# then runs on the CPU; GAN_WIDTH / GAN_BATCH / GAN_STEPS shrink the timed run for it); DEBS,
# TORCH_PREFIX, CUDA_ARCH, PYTHON, THREADS override what is found, BUILD the build directory (default: a
# fresh one under $TMPDIR). SKIP_BUILD=1 with BUILD=<an existing build> re-runs only the
# measurements. ONLY_BUILD=1 stops after building TARGETS (default: the four LibTorch programs), for
# scripts that run their own work on the GPU (bench/asr/table2_translator_gpu.sh): the programs are
# then in $TMPDIR/tsrir_cuda_check/build/bin and the libraries they open in .../deps.
# Usage (repository root): bench/gan/cuda_check.sh [OUT_DIR]    (must finish in < 8 min on 16 cores)
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out=${1:-${OUT:-/tmp/cuda_check}}
mkdir -p "$out"
work=${TMPDIR:-/tmp}/tsrir_cuda_check
rm -rf "$work"
mkdir -p "$work"
debs=${DEBS:-$root/exp/cuda_check_debs}
deps=$work/deps
build=${BUILD:-$work/build}
device=${TSRIR_CHECK_DEVICE:-cuda}
# The timed training run: the paper's width and batch (a rehearsal may shrink them).
gan_width=${GAN_WIDTH:-64} gan_batch=${GAN_BATCH:-64} gan_steps=${GAN_STEPS:-20}
cores=${THREADS:-$("$root/utils/cores")}  # threads for LibTorch and OpenMP (a loaded rehearsal machine wants 1)
start=$(date +%s)
summary=$out/summary.md
python=${PYTHON:-$(command -v python3)}

elapsed() { echo $(($(date +%s) - start)); }
note() { echo "$*" | tee -a "$summary" >&2; }
# step NAME TIMEOUT_S COMMAND...: runs with a time limit (cut to what is left of the whole run's
# budget, DEADLINE_S, default 470 s), its output in OUT_DIR/NAME.log; skipped when none is left.
deadline=${DEADLINE_S:-470}
step() {
  local name=$1 limit=$2
  shift 2
  local left=$((deadline - $(elapsed)))
  if ((left < 10)); then
    note "- \`$name\`: skipped (the run's ${deadline} s budget is spent)"
    return 99
  fi
  ((limit > left)) && limit=$left
  local t0=$(date +%s.%N) rc=0
  timeout "$limit" "$@" >"$out/$name.log" 2>&1 || rc=$?
  local t1=$(date +%s.%N)
  awk -v n="$name" -v rc="$rc" -v t0="$t0" -v t1="$t1" \
    'BEGIN {printf "- `%s`: exit %s, %.1f s wall (log: %s.log)\n", n, rc, t1 - t0, n}' | tee -a "$summary" >&2
  return $rc
}
# median of the step_s column (the last) of a loss log over steps >= 2 (the first warms up)
median_step() {
  awk -F, 'NR>2{print $NF}' "$1" | sort -g | awk '{a[NR]=$1} END{if (NR == 0) print "n/a"; else print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}'
}

: >"$summary"
note "# cuda_check.sh ($(date -u +%Y-%m-%dT%H:%MZ), device runs on: $device)"
note ""
note "## Machine"
{
  echo '```'
  uname -a
  echo "cores: $cores; load average: $(cut -d' ' -f1-3 /proc/loadavg)"
  grep -m1 'model name' /proc/cpuinfo
  nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader 2>&1 | head -4
  g++ --version | head -1
  cmake --version | head -1
  "$python" -c 'import torch, sys; print("torch", torch.__version__, "cuda", torch.version.cuda, "available", torch.cuda.is_available(), "cxx11 abi", torch._C._GLIBCXX_USE_CXX11_ABI)' 2>&1
  echo '```'
} | tee -a "$summary" >&2

note ""
note "## Dependencies ($(elapsed) s)"
# Unpack the Debian packages (dpkg -x, or ar + tar where dpkg is missing).
mkdir -p "$deps"
shopt -s nullglob
packages=("$debs"/*.deb)
for d in "${packages[@]}"; do
  if command -v dpkg >/dev/null; then
    dpkg -x "$d" "$deps"
  else
    member=$(ar t "$d" | grep '^data\.tar')
    case $member in
      *.xz) ar p "$d" "$member" | tar -xJ -C "$deps" ;;
      *.zst) ar p "$d" "$member" | tar --zstd -x -C "$deps" ;;
      *) ar p "$d" "$member" | tar -xz -C "$deps" ;;
    esac
  fi
done
note "- unpacked ${#packages[@]} Debian packages from $debs into $deps"
libdir=$deps/usr/lib/x86_64-linux-gnu
export LD_LIBRARY_PATH=$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
if [[ ${SKIP_BUILD:-0} != 1 ]]; then
note ""
note "## Build ($(elapsed) s)"
torch_prefix=${TORCH_PREFIX:-$("$python" -c 'import torch; print(torch.utils.cmake_prefix_path)')}
cmake_args=(-S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DTSRIR_FFTW_WISDOM=OFF
            "-DCMAKE_PREFIX_PATH=$deps/usr;$torch_prefix")
command -v ninja >/dev/null && cmake_args+=(-G Ninja)
if [[ $device == cuda ]]; then
  nvcc=$(command -v nvcc || ls /usr/local/cuda/bin/nvcc /usr/local/cuda-*/bin/nvcc 2>/dev/null | head -1)
  [[ -n $nvcc ]] && cmake_args+=("-DCMAKE_CUDA_COMPILER=$nvcc") && export PATH=$(dirname "$nvcc"):$PATH
  # The GPU's compute capability (9.0 on an H100/H200): CMake's CUDA language and LibTorch's
  # cmake files ask for it; no CUDA code of ours is compiled for it.
  cap=${CUDA_ARCH:-$(nvidia-smi --query-gpu=compute_cap --format=csv,noheader 2>/dev/null | head -1)}
  cap=${cap:-9.0}
  export TORCH_CUDA_ARCH_LIST=$cap
  cmake_args+=("-DCMAKE_CUDA_ARCHITECTURES=${cap/./}")
  note "- nvcc: ${nvcc:-not found}; TORCH_CUDA_ARCH_LIST=$cap, CMAKE_CUDA_ARCHITECTURES=${cap/./}"
fi
note "- LibTorch: $torch_prefix"
echo "cmake ${cmake_args[*]}" >"$out/cmake_command.txt"
step configure 180 cmake "${cmake_args[@]}" || { note "configure failed: see configure.log"; exit 1; }
grep -E "Found Torch|Caffe2: CUDA|CUDA detected|without pkg-config|Found Boost|Found GTest" "$out/configure.log" \
  | sed 's/^/    /' | tee -a "$summary" >&2
keep_going=(-k)
command -v ninja >/dev/null && keep_going=(-k 0)
# shellcheck disable=SC2086  # TARGETS is a list of names
step build 300 cmake --build "$build" -j "$cores" --target ${TARGETS:-ts-rirgan-train gas-to-real asr-train asr-decode} \
  -- "${keep_going[@]}" || { note "build failed: see build.log"; exit 1; }
[[ ${ONLY_BUILD:-0} == 1 ]] && { note "- built (ONLY_BUILD=1) in $(elapsed) s"; exit 0; }
# The tests separately: a failure there does not stop the runs.
step build_tests 150 cmake --build "$build" -j "$cores" --target torch_compat_2x_test gan_networks_test \
  -- "${keep_going[@]}"
cat "$out/build.log" "$out/build_tests.log" | grep -ciE "warning:.*deprecated" | sed 's/^/- deprecation warnings in the build: /' | tee -a "$summary" >&2
bin=$build/bin
for p in ts-rirgan-train asr-train; do
  echo "== $p" >>"$out/ldd.txt"
  ldd "$bin/$p" >>"$out/ldd.txt" 2>&1
done
note "- \`ldd ts-rirgan-train | grep -E 'torch_cuda|gomp'\`:"
grep -A200 "== ts-rirgan-train" "$out/ldd.txt" | grep -B200 -m1 "== asr-train" | grep -E "torch_cuda|gomp|not found" \
  | sed 's/^/    /' | tee -a "$summary" >&2
fi
bin=$build/bin

note ""
note "## Runs ($(elapsed) s)"
data=$work/data
step data 120 "$python" "$root/bench/gan/cuda_check_data.py" "$data" 512 64 16 || exit 1
rirs=$data/rirs
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=$cores
smi_start() { nvidia-smi --query-gpu=timestamp,utilization.gpu,memory.used --format=csv,noheader,nounits -lms 250 \
                >"$out/$1.smi.csv" 2>/dev/null & smi_pid=$!; }
smi_stop() { [[ -n ${smi_pid:-} ]] && kill "$smi_pid" 2>/dev/null; wait "$smi_pid" 2>/dev/null; smi_pid=; }
smi_peak() { awk -F', *' '{if ($2 > u) u = $2; if ($3 > m) m = $3} END {printf "peak GPU utilisation %s %%, peak GPU memory %s MiB", u, m}' "$out/$1.smi.csv" 2>/dev/null; }
train=("$bin/ts-rirgan-train" --real="$rirs/real.scp" --synthetic="$rirs/synthetic.scp" --num-threads="$cores"
       --checkpoint-every=100000 --progress-interval=5)

step gan_one_step 120 "${train[@]}" --device="$device" --steps=1 --width=8 --batch-size=4 "$work/gan_one"
tail -2 "$out/gan_one_step.log" | sed 's/^/    /' | tee -a "$summary" >&2

smi_start gan64_$device
step gan64_$device 150 "${train[@]}" --device="$device" --steps="$gan_steps" --width="$gan_width" --batch-size="$gan_batch" "$work/gan64_$device"
smi_stop
cuda_step=$(median_step "$work/gan64_$device/loss_log.csv")
note "    median s/step ($device, width $gan_width, batch $gan_batch, steps 2-$gan_steps): **$cuda_step**; $(smi_peak gan64_$device)"
# Both devices, each once (a rehearsal's "cuda" runs were on the CPU already).
devices=("$device")
[[ $device != cpu ]] && devices+=(cpu)
if [[ $device != cpu ]] && (($(elapsed) < deadline - 110)); then
  step gan64_cpu 150 "${train[@]}" --device=cpu --steps=3 --width="$gan_width" --batch-size="$gan_batch" "$work/gan64_cpu"
  cpu_step=$(median_step "$work/gan64_cpu/loss_log.csv")
  note "    median s/step (cpu, $cores threads, width $gan_width, batch $gan_batch, steps 2-3): **$cpu_step**"
  awk -v g="$cuda_step" -v c="$cpu_step" 'BEGIN {if (g > 0 && c > 0) printf "    20,000 steps: %.0f min on %s, %.1f h on the CPU\n", g * 20000 / 60, "'"$device"'", c * 20000 / 3600}' \
    | tee -a "$summary" >&2
fi

model=$work/gan64_$device
for dev in "${devices[@]}"; do
  smi_start gas_$dev
  step gas_to_real_$dev 120 "$bin/gas-to-real" --model="$model" --device="$dev" --num-threads="$cores" \
    "$rirs/synthetic.scp" "$work/gas_$dev"
  smi_stop
  grep -o "translated [0-9]* RIRs .*" "$out/gas_to_real_$dev.log" | sed 's/^/    /' | tee -a "$summary" >&2
done
if [[ $device == cuda ]]; then
  "$python" - "$work/gas_cuda" "$work/gas_cpu" <<'PY' 2>&1 | sed 's/^/    /' | tee -a "$summary" >&2
import os, struct, sys
import numpy as np
def read(path):  # RIFF/WAVE, PCM or IEEE float (also in WAVE_FORMAT_EXTENSIBLE)
    b = open(path, "rb").read()
    i, fmt, bits, data = 12, None, None, None
    while i + 8 <= len(b):
        cid, size = b[i:i + 4], struct.unpack("<I", b[i + 4:i + 8])[0]
        if cid == b"fmt ":
            fmt, bits = struct.unpack("<H", b[i + 8:i + 10])[0], struct.unpack("<H", b[i + 22:i + 24])[0]
            if fmt == 0xFFFE:
                fmt = struct.unpack("<H", b[i + 32:i + 34])[0]
        elif cid == b"data":
            data = b[i + 8:i + 8 + size]
        i += 8 + size + (size & 1)
    return np.frombuffer(data, "<f4") if fmt == 3 else np.frombuffer(data, "<i2") / 32768.0
a_dir, b_dir = sys.argv[1], sys.argv[2]
names = sorted(n for n in os.listdir(a_dir) if n.endswith(".wav"))
worst, rel = 0.0, []
for n in names:
    a, b = read(os.path.join(a_dir, n)), read(os.path.join(b_dir, n))
    worst = max(worst, float(np.max(np.abs(a - b))))
    rel.append(float(np.sqrt(np.mean((a - b) ** 2)) / max(1e-12, np.sqrt(np.mean(a ** 2)))))
print("gas-to-real cuda vs cpu over %d RIRs: max |difference| %.3g, median relative RMS difference %.3g"
      % (len(names), worst, float(np.median(rel))))
PY
fi

asr=$data/asr
asr_opts=(--num-threads="$cores" --conv-layers=1 --conv-channels=128 --rnn-layers=2 --rnn-hidden=128 --batch-size=16
          --progress-interval=5)
smi_start asr_$device
step asr_train_$device 120 "$bin/asr-train" "${asr_opts[@]}" --device="$device" --epochs=1 "$asr/train" "$work/asr"
smi_stop
step asr_resume_cpu 120 "$bin/asr-train" "${asr_opts[@]}" --device=cpu --epochs=2 --resume "$asr/train" "$work/asr"
grep -ho "trained .*" "$out/asr_train_$device.log" "$out/asr_resume_cpu.log" | sed 's/^/    /' | tee -a "$summary" >&2
for dev in "${devices[@]}"; do
  step asr_decode_$dev 120 "$bin/asr-decode" --device="$dev" --num-threads="$cores" "$work/asr" "$asr/test" \
    "$work/asr/decode_$dev"
  grep -o "decoded .*" "$out/asr_decode_$dev.log" | sed 's/^/    /' | tee -a "$summary" >&2
done
if [[ $device != cpu ]]; then
  if cmp -s "$work/asr/decode_$device/hyp" "$work/asr/decode_cpu/hyp"; then
    note "    asr-decode: the same hypotheses on $device and cpu"
  else
    note "    asr-decode: hypotheses differ between $device and cpu in $(diff "$work/asr/decode_$device/hyp" "$work/asr/decode_cpu/hyp" | grep -c '^<') utterance(s)"
  fi
fi

note ""
note "## Tests against this LibTorch ($(elapsed) s)"
step torch_compat_2x_test 60 "$bin/torch_compat_2x_test" --gtest_brief=1
if (($(elapsed) < deadline - 70)); then
  OMP_NUM_THREADS=4 step gan_networks_test 150 "$bin/gan_networks_test" --gtest_brief=1
  grep -E "PASSED|FAILED|tests ran" "$out/gan_networks_test.log" | sed 's/^/    /' | tee -a "$summary" >&2
else
  note "- gan_networks_test skipped (time)"
fi
# Every other target (all programs, tests, benchmarks, the header checks) with the time left: the
# whole toolkit against this LibTorch and compiler (-k 0: every failure is listed, not only the first).
left=$((deadline - $(elapsed)))
if [[ ${SKIP_BUILD:-0} == 1 ]]; then
  :
elif ((left > 30)); then
  step build_all "$left" cmake --build "$build" -j "$cores" -- "${keep_going[@]}"
  note "    $(grep -c '^FAILED:' "$out/build_all.log") failed build step(s); $(grep -o '\[[0-9]*/[0-9]*\]' "$out/build_all.log" | tail -1) steps reached"
  grep -A3 '^FAILED:' "$out/build_all.log" | grep -E 'error' | head -20 | sed 's/^/    /' | tee -a "$summary" >&2
else
  note "- build of all targets skipped (time)"
fi
for f in "$work"/gan64_*/loss_log.csv; do cp "$f" "$out/$(basename "$(dirname "$f")")_loss_log.csv"; done
note ""
note "Done in $(elapsed) s."
