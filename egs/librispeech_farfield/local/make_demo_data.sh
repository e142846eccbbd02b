#!/usr/bin/env bash
# The demo's embedded corpus (run.sh --demo, stage 0), made without downloads:
#   speech  recorded LibriSpeech and LibriVox utterances from <shared-data>/speech when present,
#           else sentences of conf/demo_sentences.txt synthesised with espeak-ng (stand-in);
#   RIRs    the R3VIVAL measured RIRs of <shared-data>/rirs/r3vival (resampled to 16 kHz, 16-bit)
#           when present, else a stand-in set simulated by rir-simulate for the same room,
#           positions and measured T30s (conf/r3vival_layout.txt);
#   noise   the 8 channels of the real room-noise recording <shared-data>/noise/
#           room_noise_8ch_rec_one.wav when present, else generated coloured noise (stand-in).
# Writes <out>/speech/{train_clean,dev_clean,test_clean}/{wav.scp,utt2spk,text},
# <out>/rirs/{wav/,meta.txt,rir.scp}, <out>/noise/{wav/,noise.scp} and <out>/SOURCES (one line per
# part: real or stand-in, and from where). Shared files are read in place, never copied, except
# that RIRs and noise are converted to 16 kHz 16-bit wavs (what Kaldi's tools read).
set -euo pipefail

size=small            # small (the README demo) | tiny (CI)
shared_data=""        # ../shared/data (absolute); empty or missing = stand-ins only
standin_model=gas     # rir-simulate --model for the stand-in RIRs
seed=0
layout=conf/r3vival_layout.txt
sentences=conf/demo_sentences.txt
help_message="Usage: $0 [--size small|tiny] [--shared-data <dir>] [--seed N] <out-dir>"
. ./local/parse_options.sh
[ $# -eq 1 ] || { echo "$help_message" >&2; exit 1; }
out=$1
case $size in small|tiny) ;; *) echo "$0: --size must be small or tiny, got '$size'" >&2; exit 1 ;; esac
for f in "$layout" "$sentences"; do [ -f "$f" ] || { echo "$0: missing $f" >&2; exit 1; }; done

tmp=$out.tmp.$$
rm -rf "$tmp"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp"/speech/{train_clean,dev_clean,test_clean} "$tmp"/rirs/wav "$tmp"/noise/wav

have() { [ -n "$shared_data" ] && [ -e "$shared_data/$1" ]; }

# ---- speech --------------------------------------------------------------------------------
add_utt() {  # <set> <utt> <spk> <rxfilename> <text>
  printf '%s %s\n' "$2" "$4" >>"$tmp/speech/$1/wav.scp"
  printf '%s %s\n' "$2" "$3" >>"$tmp/speech/$1/utt2spk"
  printf '%s %s\n' "$2" "$5" >>"$tmp/speech/$1/text"
}
# A pocketsphinx transcription line "<s> words </s> (id)" -> upper-case words.
ps_text() { grep "($2)\$" "$1" | sed 's/<s>//; s/<\/s>//; s/([^)]*)$//' | tr '[:lower:]' '[:upper:]' | awk '{$1 = $1; print}'; }

if have speech/librispeech/trans.txt && have speech/pocketsphinx/transcription; then
  ls_dir=$shared_data/speech/librispeech
  ps_dir=$shared_data/speech/pocketsphinx
  if [ "$size" = tiny ]; then
    test_utts="1089-134686-0001 1221-135766-0002"; cards="001"; austen="0880 0930 0890"
  else
    test_utts="1089-134686-0001 1221-135766-0001 1221-135766-0002"; cards="001 002 003 004 005"
    austen="0870 0880 0890 0920 0930"
  fi
  # test_clean: LibriSpeech test-clean utterances (speaker = <reader>-<chapter>, as Kaldi's).
  for u in $test_utts; do
    text=$(awk -F'\t' -v u="$u" '$1 == u {print $2}' "$ls_dir/trans.txt")
    [ -n "$text" ] || { echo "$0: no transcript for $u in $ls_dir/trans.txt" >&2; exit 1; }
    add_utt test_clean "$u" "${u%-*}" "$ls_dir/$u.wav" "$text"
  done
  # dev_clean: a LibriSpeech dev-clean utterance (FLAC, read through Kaldi's usual flac pipe) and
  # read card names (LibriSpeech's 2412-153948-0001 has no transcript here and is not used).
  u=2412-153948-0000
  text=$(awk -v u="lbi-$u" '$1 == u {$1 = ""; print substr($0, 2)}' "$ls_dir/mini_librispeech_text.txt")
  [ -n "$text" ] || { echo "$0: no transcript for $u in $ls_dir/mini_librispeech_text.txt" >&2; exit 1; }
  add_utt dev_clean "$u" "${u%-*}" "flac -c -d -s $ls_dir/$u.flac |" "$text"
  for c in $cards; do
    add_utt dev_clean "ps-cards-$c" ps-cards "$ps_dir/cards/$c.wav" "$(ps_text "$ps_dir/cards/cards.transcription" "$c")"
  done
  # train_clean: LibriVox "Sense and Sensibility" utterances.
  for a in $austen; do
    id=sense_and_sensibility_01_austen_64kb-$a
    add_utt train_clean "ps-austen-$a" ps-austen "$ps_dir/$id.wav" "$(ps_text "$ps_dir/transcription" "$id")"
  done
  echo "speech real: LibriSpeech test-clean/dev-clean and LibriVox utterances from $shared_data/speech" >>"$tmp/SOURCES"
else
  command -v espeak-ng >/dev/null || { echo "$0: no $shared_data/speech and no espeak-ng (utils/bootstrap.sh installs it)" >&2; exit 1; }
  mkdir -p "$tmp/speech/wav"
  n_train=0; n_dev=0; n_test=0
  grep -v '^#' "$sentences" | while read -r set spk voice num text; do
    [ -n "$set" ] || continue
    if [ "$size" = tiny ]; then
      case $set in
        train_clean) n_train=$((n_train + 1)); [ $n_train -le 3 ] || continue ;;
        dev_clean) n_dev=$((n_dev + 1)); [ $n_dev -le 1 ] || continue ;;
        test_clean) n_test=$((n_test + 1)); [ $n_test -le 2 ] || continue ;;
      esac
    fi
    utt=$spk-$num
    wav=$tmp/speech/wav/$utt.wav
    espeak-ng -v "$voice" -s 150 -w "$tmp/speech/wav/$utt.22k.wav" "$text"
    # -R everywhere: sox dithers when it writes 16 bits, with a random seed unless -R; without it
    # no two demo runs gave the same audio (nor, through it, the same fits and tables).
    sox -R "$tmp/speech/wav/$utt.22k.wav" -r 16000 -b 16 "$wav"
    rm "$tmp/speech/wav/$utt.22k.wav"
    add_utt "$set" "$utt" "$spk" "$out/speech/wav/$utt.wav" "$text"
  done
  echo "speech STAND-IN: sentences of $sentences synthesised with espeak-ng (no $shared_data/speech)" >>"$tmp/SOURCES"
fi
for s in train_clean dev_clean test_clean; do
  [ -s "$tmp/speech/$s/wav.scp" ] || { echo "$0: no utterances for $s" >&2; exit 1; }
done

# ---- RIRs ------------------------------------------------------------------------------------
read -r _ Lx Ly Lz < <(grep '^room ' "$layout")
read -r _ mx my mz < <(grep '^mic ' "$layout")
conditions=$(awk '$1 == "condition" {print $2}' "$layout")
sources=$(awk '$1 == "source" {print $2}' "$layout")
if [ "$size" = tiny ]; then
  conditions="000 050 100"
  sources="S000-150 S030-200 S090-150 S150-300 S180-200 S240-150 S300-200 SBG2"
fi
for c in $conditions; do
  for s in $sources; do
    read -r _ _ sx sy sz < <(awk -v s="$s" '$1 == "source" && $2 == s' "$layout")
    # rir id, room id, room size, source, microphone (the metadata table of local/split_rirs.sh)
    echo "r3v$c-$s r3vival-a$c $Lx $Ly $Lz $sx $sy $sz $mx $my $mz"
  done
done >"$tmp/rirs/meta.txt"

if have rirs/r3vival; then
  while read -r id _; do
    c=${id%%-*}; c=${c#r3v}; s=${id#*-}
    src=$shared_data/rirs/r3vival/RLRVarAcLab_Absorptive_${c}_${s}_R1_FRL10cm_ch7.wav
    [ -f "$src" ] || { echo "$0: missing $src" >&2; exit 1; }
    # -G: guard against clipping by the resampler (the files peak below 0.65).
    sox -R -G "$src" -r 16000 -b 16 "$tmp/rirs/wav/$id.wav"
    echo "$id $out/rirs/wav/$id.wav"
  done <"$tmp/rirs/meta.txt" >"$tmp/rirs/rir.scp"
  echo "rirs real: R3VIVAL measured RIRs (omni ch7, $(wc -l <"$tmp/rirs/rir.scp") of them) from $shared_data/rirs/r3vival" >>"$tmp/SOURCES"
else
  command -v rir-simulate >/dev/null || { echo "$0: rir-simulate is not on PATH (build the toolkit first)" >&2; exit 1; }
  # The measured T30s of each condition as per-band targets (62.5 Hz = 125 Hz, 8 kHz = 4 kHz).
  while read -r id room lx ly lz sx sy sz mx2 my2 mz2; do
    c=${id%%-*}; c=${c#r3v}
    t60=$(awk -v c="$c" '$1 == "condition" && $2 == c {printf "%s,%s,%s,%s,%s,%s,%s,%s", $3,$3,$4,$5,$6,$7,$8,$8}' "$layout")
    echo "$id room=$lx,$ly,$lz src=$sx,$sy,$sz mic=$mx2,$my2,$mz2 t60=$t60 room-id=$room"
  done <"$tmp/rirs/meta.txt" >"$tmp/rirs/standin_room_list"
  rir-simulate --model="$standin_model" --seed=$((seed + 1000)) --fs=16000 --length=1.0 \
    "$tmp/rirs/standin_room_list" "$tmp/rirs/sim" 2>"$tmp/rirs/standin.log" || {
    cat "$tmp/rirs/standin.log" >&2; echo "$0: rir-simulate failed for the stand-in RIRs" >&2; exit 1; }
  mv "$tmp"/rirs/sim/*.wav "$tmp/rirs/wav/"
  rm -rf "$tmp/rirs/sim"
  awk -v d="$out/rirs/wav" '{print $1, d "/" $1 ".wav"}' "$tmp/rirs/meta.txt" >"$tmp/rirs/rir.scp"
  echo "rirs STAND-IN: simulated by rir-simulate --model=$standin_model for the R3VIVAL room, positions and measured T30s (no $shared_data/rirs/r3vival): the 'real' row of Table 1 is simulated" >>"$tmp/SOURCES"
fi

# ---- noise -----------------------------------------------------------------------------------
if have noise/room_noise_8ch_rec_one.wav; then
  channels="1 2 3 4 5 6 7 8"
  [ "$size" = tiny ] && channels="1 2"
  for ch in $channels; do
    sox -R -G "$shared_data/noise/room_noise_8ch_rec_one.wav" -r 16000 -b 16 "$tmp/noise/wav/roomnoise-ch$ch.wav" remix "$ch"
    echo "roomnoise-ch$ch $out/noise/wav/roomnoise-ch$ch.wav"
  done >"$tmp/noise/noise.scp"
  echo "noise real: room noise re-recorded by an 8-mic array ($shared_data/noise/room_noise_8ch_rec_one.wav), one noise per channel" >>"$tmp/SOURCES"
else
  # sox -R: repeatable noise. Four colours of stationary background noise, 20 s each.
  i=0
  for effect in "pinknoise lowpass 2000" "brownnoise" "pinknoise highpass 100 lowpass 4000 tremolo 0.3 40" "whitenoise lowpass 1000"; do
    i=$((i + 1))
    # shellcheck disable=SC2086
    sox -R -n -r 16000 -b 16 -c 1 "$tmp/noise/wav/gen$i.wav" synth 20 $effect gain -n -20
    echo "gen$i $out/noise/wav/gen$i.wav"
  done >"$tmp/noise/noise.scp"
  echo "noise STAND-IN: generated coloured noise (sox synth; no $shared_data/noise)" >>"$tmp/SOURCES"
fi

rm -rf "$out"
mv "$tmp" "$out"
trap - EXIT
