// rir-simulate: the toolkit's geometric acoustic simulator (shoebox image sources + diffuse tail).
#include <string>

#include "io/audio_io.h"
#include "sim/model.h"
#include "sim/room_list.h"
#include "sim/simulate.h"
#include "io/owned_output.h"
#include "util/cli.h"

int main(int argc, char** argv) {
  using namespace tsrir;
  return run_program("rir-simulate", [&]() {
    const std::string usage =
        "Simulates one RIR per line of a room list with a geometric acoustic model and writes\n"
        "<out-dir>/<rir-id>.wav, <out-dir>/rir.scp and <out-dir>/rir_list (Kaldi\n"
        "reverberate_data_dir.py format: --rir-id <id> --room-id <room> <path>).\n"
        "Amplitudes are physical (direct sound 1/(4 pi r)), so a source within ~8 cm of the microphone\n"
        "exceeds int16 full scale (an error; use --format=float). The stochastic part is seeded by\n"
        "--seed and the rir id, so results do not depend on --num-threads.\n\n"
        "Usage: rir-simulate [options] <room-list> <out-dir>\n"
        "Example:\n"
        "  echo 'r1 room=6,4.5,3 src=2,1.5,1.6 mic=4,3,1.2 t60=0.6' > rooms.txt\n"
        "  rir-simulate --sample-rate=16000 --length=auto --num-threads=4 rooms.txt data/sim_rirs\n\n" +
        sim::room_list_keys_help() +
        "\nModel components (--model=a+b+..., parameters as name:key=value,key=value):\n" +
        sim::model_components_help();
    CommandLine cli("rir-simulate", usage);
    sim::SimulateOptions options;
    options.Register(&cli);
    OutputPolicy policy(cli.program());
    policy.Register(&cli);
    const std::vector<std::string> args = cli.parse(argc, argv, 2, 2);
    install_output_policy(policy);
    run_inputs()->add(args[0]);
    const std::vector<sim::RoomSpec> rooms = sim::read_room_list(args[0]);
    log_info("simulating " + std::to_string(rooms.size()) + " RIRs with model '" + options.model + "'");
    sim::simulate_room_list(rooms, args[1], options);
    log_info("wrote " + std::to_string(rooms.size()) + " RIRs to " + args[1]);
    return 0;
  });
}
