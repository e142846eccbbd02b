# Sourced by bench/sim/array_speed.sh and array_floor.sh: the machine line, then in DIR the room lists
# both time, one.txt (N source positions, one microphone each) and eight.txt (the same positions with
# an 8-microphone circular array of radius 4.25 cm, circular8.txt).
#   write_array_lists DIR N
array_lists_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
write_array_lists() {
  echo "machine: $("$array_lists_root/utils/cores") cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u '+%F %H:%M UTC')"
  printf 'circular n=8 radius_m=0.0425\n' > "$1/circular8.txt"
  for i in $(seq 1 "$2"); do
    x=$(awk -v i="$i" 'BEGIN { printf "%.3f", 3.0 + 2.5 * ((i * 37) % 100) / 100 }')
    echo "p$i room=7,6,3 src=1.5,2,1.5 mic=$x,3.5,1.4 t60=0.6"
  done > "$1/one.txt"
  sed 's/ t60=/ array=circular8.txt t60=/' "$1/one.txt" > "$1/eight.txt"
}
