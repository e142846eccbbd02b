#!/usr/bin/env python3
"""pyroomacoustics side of the simulator benchmarks (issue 20): renders one room of rooms.txt
with pyroomacoustics' ShoeBox, image sources only or hybrid ISM + ray tracing (compiled libroom),
and prints the median time per RIR of Room.compute_rir() (interpreter start and imports excluded).

  PYTHONPATH=$PRA_PYTHONPATH python3 pra_sim.py ROOM ism|hybrid REPS THREADS [out.wav] [--mics=N]
  --mics=N: a circular array of N microphones, radius 5 cm, horizontal, centred on the room's mic
  (issue 33's array benchmark, bench/peers/array_speed.sh); the time is that of the whole array.
Prints: mode=... rirs=R cpu_s_per_rir=<median process CPU s> wall_s_per_rir=<median> length_s=<RIR>
  ism:    max_order from pra.inverse_sabine(target T60, room) (pra's documented recipe), no air absorption
  hybrid: max_order=3 + ray tracing with pra's default settings (set_ray_tracing()), scattering 0.1
Both use the energy absorption of rooms.py (Eyring inversion of the target T60), as tsrir does.
"""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rooms  # noqa: E402
import numpy as np  # noqa: E402
import pyroomacoustics as pra  # noqa: E402

FS = 16000


def circular_array(centre, n, radius_m=0.05):
    angles = 2 * np.pi * np.arange(n) / n
    return np.array([centre[0] + radius_m * np.cos(angles), centre[1] + radius_m * np.sin(angles),
                     np.full(n, centre[2])])


def make_room(r, mode, mics=1):
    if mode == "ism":
        _, max_order = pra.inverse_sabine(r["t60"], r["dim"])
        room = pra.ShoeBox(r["dim"], fs=FS, materials=pra.Material(r["alpha"]), max_order=max_order,
                           air_absorption=False)
    elif mode == "hybrid":
        room = pra.ShoeBox(r["dim"], fs=FS, materials=pra.Material(r["alpha"], 0.1), max_order=3,
                           ray_tracing=True, air_absorption=False)
        room.set_ray_tracing()
    else:
        sys.exit("mode must be ism or hybrid")
    room.add_source(r["src"])
    if mics == 1:
        room.add_microphone(np.array(r["mic"]))
    else:
        room.add_microphone_array(circular_array(r["mic"], mics))
    return room


def main():
    mics = 1
    for a in [a for a in sys.argv if a.startswith("--mics=")]:
        mics = int(a.split("=", 1)[1])
        sys.argv.remove(a)
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    r = rooms.by_name(sys.argv[1])
    mode, reps, threads = sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    pra.constants.set("num_threads", threads)
    cpu, wall, length = [], [], 0
    for k in range(reps):
        room = make_room(r, mode, mics)  # room set-up is not timed; compute_rir() is the simulation
        c0, w0 = time.process_time(), time.perf_counter()
        room.compute_rir()
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - w0)
        h = np.asarray(room.rir[0][0], dtype=np.float32)
        length = len(h) / FS
        if k == 0 and len(sys.argv) > 5:
            import scipy.io.wavfile
            scipy.io.wavfile.write(sys.argv[5], FS, h)
    print("mode=%s rirs=%d cpu_s_per_rir=%.6f wall_s_per_rir=%.6f length_s=%.3f max_order=%d" %
          (mode, reps, float(np.median(cpu)), float(np.median(wall)), length, room.max_order))


if __name__ == "__main__":
    main()
