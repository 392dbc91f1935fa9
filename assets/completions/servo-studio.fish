# Print an optspec for argparse to handle cmd's options that are independent of any subcommand.
function __fish_servo_studio_global_optspecs
    string join \n h/help V/version
end

function __fish_servo_studio_needs_command
    # Figure out if the current invocation already has a command.
    set -l cmd (commandline -opc)
    set -e cmd[1]
    argparse -s (__fish_servo_studio_global_optspecs) -- $cmd 2>/dev/null
    or return
    if set -q argv[1]
        # Also print the command, so this can be used to figure out what it is.
        echo $argv[1]
        return 1
    end
    return 0
end

function __fish_servo_studio_using_subcommand
    set -l cmd (__fish_servo_studio_needs_command)
    test -z "$cmd"
    and return 1
    contains -- $cmd[1] $argv
end

complete -c servo-studio -n "__fish_servo_studio_needs_command" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -s V -l version -d 'Print version'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "check" -d 'Check a project file (or a PLEN2 motion.json, or a folder of them) and print every problem with its location. Exits 1 when there is an error (warnings alone exit 0)'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "ports" -d 'List the serial ports this computer sees'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "completions" -d 'Print the shell completions for SHELL (bash, zsh, fish, elvish, powershell) — e.g. `servo-studio completions bash > ~/.local/share/bash-completion/completions/servo-studio`'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "man" -d 'Write a man page for the command and each subcommand into a folder (what the package installs)'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "audio-info" -d 'Read a sound (WAV, FLAC, MP3, OGG/Vorbis) and print one JSON object: `duration_s`, `sample_rate`, `channels`, `onsets_s` (seconds). Exits 1 when it cannot be read'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "follow-audio" -d 'Follow a sound\'s loudness with one servo (--servo N) or PLEN2 joint (--joint NAME): closed in silence, open at the loudest, fitted into the board\'s steps or frames within the tolerance. Servo board: writes a project with one action per step and macro 1 running them; PLEN2: a motion.json'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "probe" -d 'The connection doctor: which family answers on a port (or on every port), at which baud, what it says of itself, and how its link delivers. Sends only requests that change nothing on a servo board, a PLEN2 or an rFLEX base. Exits 1 when nothing answered'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "sim" -d 'Run an emulated board. Prints the port to connect to on the first line'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "play" -d 'Play a show with no window: connect every device (saying which answered), play the show with its sound (or silent, said) on every board together, each run\'s start, skew and end logged; Ctrl-C / SIGTERM stop every device (bases brake) and exit 130 / 143. The boards must hold the show\'s content (servo-studio import). docs/show.md'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "serve" -d 'Remote control with no window: hold every device of a show connected and take HTTP + JSON (and OSC with --osc) from cue software and control surfaces — play, stop, pose, drive (with heartbeats), status as Server-Sent Events. Loopback only unless --token-file. Ctrl-C / SIGTERM stop every device and exit 130 / 143. docs/remote.md'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "export" -d 'Read everything from a board into a project file'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "import" -d 'Write a project file onto a board: validates, backs the board up, clears it, writes, and verifies. A file with validation errors (a backup of content Servo Studio would not author) needs --force'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "gui" -d 'Open the editor window (the default with no command)'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "rflex" -d 'Drive an rFLEX mobile base, or read its sensors'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "board" -d 'Board status'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "trajectory" -d 'Write what the robot outputs over time to a CSV file, one row per board update: PLEN2, one per 32.768 ms cycle from `$PM` (the frame value in tenths of a degree relative to home, before clamping); servo board, one per 10 ms (the angle in degrees). `t_ms`, then one column per joint or servo'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "convert" -d 'Convert motions from another tool (Pololu Maestro settings file, RoboPlus Motion .mtn, R+ Motion .mtnx, Blender servo-animation JSON) into a servo or PLEN2 project, or a project (or one of those files) into a Maestro settings file or Blender JSON. Prints what was converted, approximated and dropped (docs/import-export.md)'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "fit" -d 'Fit a recording (the CSV `trajectory` writes: `t_ms`, then a column per joint or servo by name; PLEN2 values in tenths of a degree relative to home, servo values in degrees; any sample rate) into the fewest frames or steps whose playback on the board stays within the tolerance at every update. PLEN2: writes a motion.json; servo board: a project with one action per step and macro 1 running them in order'
complete -c servo-studio -n "__fish_servo_studio_needs_command" -f -a "help" -d 'Print this message or the help of the given subcommand(s)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand check" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand ports" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand completions" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand man" -l out -d 'The folder' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand man" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand audio-info" -l sensitivity -d 'How readily a rise counts as an onset, 0 (only the strongest) to 1 (every rise)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand audio-info" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l protocol -d 'The board that plays it: plen2 or servo' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l servo -d 'The servo that follows (servo board), 0–254' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l joint -d 'The joint that follows (PLEN2), by its name (`left_shoulder_pitch`…)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l closed -d 'The angle in silence, degrees (PLEN2: relative to home)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l open -d 'The angle at the loudest, degrees' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l attack-ms -d 'Time to open about two thirds of the way, ms' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l release-ms -d 'Time to close about two thirds of the way, ms' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l threshold-db -d 'Below this level (dB of full scale) the axis stays closed' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l tolerance-deg -d 'How far the board\'s playback may stray from the followed curve, degrees' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l max-frames -d 'At most this many frames or steps (PLEN2: 20, what a motion holds)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l from-slot -d 'PLEN2: a chain of motions in the slots from this one on (each up to 20 frames, jumping to the next, played as one), written as a project — into --out when it is a PLEN2 project already, replacing what those slots hold — as the editor\'s "from slot" does. Without it: one motion.json' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l name -d 'The motion\'s or macro\'s name (default: the sound\'s file name)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l out -d 'The file to write' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -l force -d 'Replace the output file even when it is read-only'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand follow-audio" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand probe" -l port -d 'The port (default: every port this computer sees)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand probe" -l baud -d 'Ask every family at this line rate (default: each family\'s own)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand probe" -l timeout-ms -d 'How long a request may wait for its reply to begin, ms (default 500)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand probe" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l tcp -d 'Serve on TCP at this address, e.g. 127.0.0.1:5000 (port 0 picks one)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l state -d 'Preload the board from this project file (servo board; PLEN2: a project, motion.json or folder)' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l baud -d 'Servo board: emulate this line rate, 300..=4000000 (bytes take 10 bits each); default: as fast as the link goes' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l turnaround-ms -d 'Servo board: time between a request and its response, 0..=60000 ms (default 0)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l memory -d 'Servo board: its memory in bytes (default 262144)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l faults -d 'Servo board: faults to inject, e.g. garbage-every=3,drop-every=7,disconnect-after=40,refuse-add=42' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l noise -d 'rFLEX base: line noise on the output, e.g. garbage-every=5,corrupt-every=7,cut-every=11' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l robot -d 'rFLEX base: the robot, b21r (default), atrv-jr or magellan (its own sonars and bumpers)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l room -d 'rFLEX base: the room it stands in, WIDTHxDEPTH metres (default 4.2x2.8)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l start -d 'rFLEX base: where it starts, X,Y,THETA_DEG — metres from the room\'s centre (x along its width) and its heading in degrees from +x (default 0,0,0)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l link -d 'PLEN2: the line to the robot: clean (default), bursty[=MS][,whole] (a Bluetooth LE bridge, 7.5–30 ms connection interval, 15 by default; `whole`: replies buffered and delivered whole at the next event), late=MS (writes held back up to MS ms) or slow=BAUD' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l hardware-error -d 'A servo bus: a servo\'s hardware error, ID:KIND@SECONDS after the bus first hears a packet (KIND: input-voltage, overheating, overload), e.g. 2:overheating@5; repeatable' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l log -d 'Write every command the board receives to FILE, a line each: the system\'s monotonic clock in nanoseconds when the board took it in, then the command (any family)' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l protocol -d 'Which family to emulate: servo, plen2 or rflex' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l pty -d 'Serve on a pseudo-terminal (the default on Linux and macOS)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l body-panels-only -d 'rFLEX base: report only a B21r\'s six body panels (0x40–0x45), for the ROS b21_node'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -l stuffed -d 'rFLEX base: send every frame stuffed'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand sim" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand play" -l device -d 'Where a device is connected, NAME=PORT (overrides the show\'s port; repeat for each)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand play" -l loop -d 'Plays the show this many times (default 1; with --at or --wait-gamepad, run after run until stopped)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand play" -l at -d 'Starts a run at this local time, HH:MM (repeat for several; each day)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand play" -l wait-gamepad -d 'Before each run, waits for a press of this button on this gamepad (an event device, e.g. /dev/input/event5:BTN_SOUTH): a visitor starts the show' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand play" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand serve" -l device -d 'Where a device is connected, NAME=PORT (overrides the show\'s port; repeat for each)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand serve" -l listen -d 'Where HTTP listens (another address than loopback needs --token-file)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand serve" -l osc -d 'Also take OSC over UDP on this port (on --listen\'s address)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand serve" -l token-file -d 'A file whose first line is the secret every request must bear (Authorization: Bearer …; OSC: the first argument)' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand serve" -l queue -d 'A play on a device that is playing waits its turn (else it is refused with 409)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand serve" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand export" -l port -d 'Serial port (/dev/ttyUSB0, COM3) or tcp://HOST:PORT' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand export" -l baud -d 'Line rate of a serial port, 300..=4000000 (default: the family\'s, 115200 for servo boards)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand export" -l timeout-ms -d 'How long the device may take to answer, in milliseconds (1..=600000), on top of the time the bytes need on the line (default: 1000; 600 for PLEN2)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand export" -l protocol -d 'The board\'s family: servo, plen2 or rflex (default: the project file\'s, else servo)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand export" -l pacing -d 'PLEN2: how uploads are paced — fast, adaptive (the default: widens when the link shows it is late or bursty) or safe (the official 32 bytes, then 50 ms)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand export" -l out -d 'The project file to write' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand export" -l slots -d 'PLEN2: the slots to read, e.g. 0-19,70 (default: all 90)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand export" -l force -d 'Replace the output file even when it is read-only'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand export" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l port -d 'Serial port (/dev/ttyUSB0, COM3) or tcp://HOST:PORT' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l baud -d 'Line rate of a serial port, 300..=4000000 (default: the family\'s, 115200 for servo boards)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l timeout-ms -d 'How long the device may take to answer, in milliseconds (1..=600000), on top of the time the bytes need on the line (default: 1000; 600 for PLEN2)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l protocol -d 'The board\'s family: servo, plen2 or rflex (default: the project file\'s, else servo)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l pacing -d 'PLEN2: how uploads are paced — fast, adaptive (the default: widens when the link shows it is late or bursty) or safe (the official 32 bytes, then 50 ms)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l in -d 'The project file to upload' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l backup-dir -d 'Folder for the backup (default: the current folder)' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l yes -d 'Do not ask for confirmation'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l force -d 'Write even if validation finds errors (restores a backup exactly)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -l no-backup -d 'Do not save a backup of the board first'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand import" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand gui" -l protocol -d 'The board family to start with (default: the project file\'s, else the last one used)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand gui" -l import -d 'Open another tool\'s file (Maestro settings, .mtn, .mtnx, Blender JSON) in the import window' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand gui" -l show -d 'Open a show (or a project as a show of one device) in the show window' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand gui" -l demo -d 'Start connected to the built-in emulated board (with a sample robot when no file is given)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand gui" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and not __fish_seen_subcommand_from status drive teleop help" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and not __fish_seen_subcommand_from status drive teleop help" -f -a "status" -d 'Start the reports, wait for one full set (status, odometry on both axes, a full sonar sweep, digital I/O), print it as one JSON object, shut the reports down'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and not __fish_seen_subcommand_from status drive teleop help" -f -a "drive" -d 'Release the brake, drive for a while at 10 Hz, stop, and shut down with the brake set'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and not __fish_seen_subcommand_from status drive teleop help" -f -a "teleop" -d 'Drive a base from a gamepad: hold the dead-man button (the left shoulder, BTN_TL) and the left stick drives (up forward, left turns left), scaled to the robot\'s top speeds, with a dead zone. The base is stopped at once when the dead-man is released, the stick centred, the gamepad\'s events dropped (until known again) or the gamepad gone — then the brake is set and the command exits 1 — and on Ctrl-C or kill'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and not __fish_seen_subcommand_from status drive teleop help" -f -a "help" -d 'Print this message or the help of the given subcommand(s)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from status" -l port -d 'Serial port (/dev/ttyUSB0, COM3) or tcp://HOST:PORT' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from status" -l baud -d 'Line rate of a serial port, 300..=4000000 (default: the family\'s, 115200 for servo boards)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from status" -l timeout-ms -d 'How long the device may take to answer, in milliseconds (1..=600000), on top of the time the bytes need on the line (default: 1000; 600 for PLEN2)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from status" -l protocol -d 'The board\'s family: servo, plen2 or rflex (default: the project file\'s, else servo)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from status" -l pacing -d 'PLEN2: how uploads are paced — fast, adaptive (the default: widens when the link shows it is late or bursty) or safe (the official 32 bytes, then 50 ms)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from status" -l robot -d 'The robot: b21r, atrv-jr or magellan (its conversion constants)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from status" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l port -d 'Serial port (/dev/ttyUSB0, COM3) or tcp://HOST:PORT' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l baud -d 'Line rate of a serial port, 300..=4000000 (default: the family\'s, 115200 for servo boards)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l timeout-ms -d 'How long the device may take to answer, in milliseconds (1..=600000), on top of the time the bytes need on the line (default: 1000; 600 for PLEN2)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l protocol -d 'The board\'s family: servo, plen2 or rflex (default: the project file\'s, else servo)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l pacing -d 'PLEN2: how uploads are paced — fast, adaptive (the default: widens when the link shows it is late or bursty) or safe (the official 32 bytes, then 50 ms)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l robot -d 'The robot: b21r, atrv-jr or magellan (its conversion constants)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l speed -d 'Translational speed, m/s (negative: backwards)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l turn -d 'Rotational speed, rad/s (positive: left)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l accel -d 'Translational acceleration, m/s²' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -l seconds -d 'How long to drive, seconds' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from drive" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l port -d 'Serial port (/dev/ttyUSB0, COM3) or tcp://HOST:PORT' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l baud -d 'Line rate of a serial port, 300..=4000000 (default: the family\'s, 115200 for servo boards)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l timeout-ms -d 'How long the device may take to answer, in milliseconds (1..=600000), on top of the time the bytes need on the line (default: 1000; 600 for PLEN2)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l protocol -d 'The board\'s family: servo, plen2 or rflex (default: the project file\'s, else servo)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l pacing -d 'PLEN2: how uploads are paced — fast, adaptive (the default: widens when the link shows it is late or bursty) or safe (the official 32 bytes, then 50 ms)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l robot -d 'The robot: b21r, atrv-jr or magellan (its conversion constants)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l gamepad -d 'The gamepad: an event device (/dev/input/eventN), or a file or named pipe of Linux `struct input_event` records' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l speed -d 'Full stick forward, m/s (default: the robot\'s top speed)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l turn -d 'Full stick to the side, rad/s (default: the robot\'s top turn rate)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l accel -d 'Acceleration, m/s²' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l axis-range -d 'The raw values the gamepad path\'s axes span (an event device says its own)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l dead-zone -d 'The part of the stick around its centre that counts as centred, 0 to 0.9' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -l deadman -d 'The dead-man button, by its kernel name (BTN_TL, BTN_TR, BTN_SOUTH, …)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from teleop" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from help" -f -a "status" -d 'Start the reports, wait for one full set (status, odometry on both axes, a full sonar sweep, digital I/O), print it as one JSON object, shut the reports down'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from help" -f -a "drive" -d 'Release the brake, drive for a while at 10 Hz, stop, and shut down with the brake set'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from help" -f -a "teleop" -d 'Drive a base from a gamepad: hold the dead-man button (the left shoulder, BTN_TL) and the left stick drives (up forward, left turns left), scaled to the robot\'s top speeds, with a dead zone. The base is stopped at once when the dead-man is released, the stick centred, the gamepad\'s events dropped (until known again) or the gamepad gone — then the brake is set and the command exits 1 — and on Ctrl-C or kill'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand rflex; and __fish_seen_subcommand_from help" -f -a "help" -d 'Print this message or the help of the given subcommand(s)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and not __fish_seen_subcommand_from info help" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and not __fish_seen_subcommand_from info help" -f -a "info" -d 'Project id, memory, battery and servos'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and not __fish_seen_subcommand_from info help" -f -a "help" -d 'Print this message or the help of the given subcommand(s)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and __fish_seen_subcommand_from info" -l port -d 'Serial port (/dev/ttyUSB0, COM3) or tcp://HOST:PORT' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and __fish_seen_subcommand_from info" -l baud -d 'Line rate of a serial port, 300..=4000000 (default: the family\'s, 115200 for servo boards)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and __fish_seen_subcommand_from info" -l timeout-ms -d 'How long the device may take to answer, in milliseconds (1..=600000), on top of the time the bytes need on the line (default: 1000; 600 for PLEN2)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and __fish_seen_subcommand_from info" -l protocol -d 'The board\'s family: servo, plen2 or rflex (default: the project file\'s, else servo)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and __fish_seen_subcommand_from info" -l pacing -d 'PLEN2: how uploads are paced — fast, adaptive (the default: widens when the link shows it is late or bursty) or safe (the official 32 bytes, then 50 ms)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and __fish_seen_subcommand_from info" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and __fish_seen_subcommand_from help" -f -a "info" -d 'Project id, memory, battery and servos'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand board; and __fish_seen_subcommand_from help" -f -a "help" -d 'Print this message or the help of the given subcommand(s)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand trajectory" -l slot -d 'PLEN2: the motion\'s slot (0..=89)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand trajectory" -l action -d 'Servo board: the action\'s id' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand trajectory" -l macro -d 'Servo board: the macro\'s id' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand trajectory" -l from-slot -d 'PLEN2: the motion played before (its last frame is where this one starts; default: power-up, all zeros)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand trajectory" -l seconds -d 'At most this long, above 0 and up to 3600 s (a motion that never ends stops here)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand trajectory" -l out -d 'The CSV file to write' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand trajectory" -l force -d 'Replace the output file even when it is read-only'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand trajectory" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l from -d 'Its format (default: told from the content): maestro, mtn, mtnx or blender' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l to -d 'What to write: servo, plen2 or dynamixel (a project), maestro (a settings file) or blender (add-on JSON)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l map -d 'A joint map (JSON): which channel drives which servo or joint, with offset, direction and scale' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l sequence -d 'Only this Maestro sequence / R+ page or flow (and what it plays); exporting: this macro or motion' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l page -d 'Only this RoboPlus page (and the pages it leads to); exporting a PLEN2 motion: its slot' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l tolerance-deg -d 'How far a fitted animation (Blender) may stray from the source, degrees' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l fps -d 'Frames per second of Blender JSON written, 1..=1000' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l save-map -d 'Also write the joint map used (guessed where --map says nothing), to edit and give again with --map' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l out -d 'The file to write' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -l force -d 'Replace the output file even when it is read-only'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand convert" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand fit" -l protocol -d 'The board that plays it: plen2 or servo' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand fit" -l tolerance-deg -d 'How far the board\'s playback may stray from the recording at any update, degrees' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand fit" -l max-frames -d 'At most this many frames or steps (PLEN2: 20, what a motion holds)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand fit" -l name -d 'The motion\'s or macro\'s name (default: the recording\'s file name)' -r
complete -c servo-studio -n "__fish_servo_studio_using_subcommand fit" -l out -d 'The file to write' -r -F
complete -c servo-studio -n "__fish_servo_studio_using_subcommand fit" -l force -d 'Replace the output file even when it is read-only'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand fit" -s h -l help -d 'Print help'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "check" -d 'Check a project file (or a PLEN2 motion.json, or a folder of them) and print every problem with its location. Exits 1 when there is an error (warnings alone exit 0)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "ports" -d 'List the serial ports this computer sees'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "completions" -d 'Print the shell completions for SHELL (bash, zsh, fish, elvish, powershell) — e.g. `servo-studio completions bash > ~/.local/share/bash-completion/completions/servo-studio`'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "man" -d 'Write a man page for the command and each subcommand into a folder (what the package installs)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "audio-info" -d 'Read a sound (WAV, FLAC, MP3, OGG/Vorbis) and print one JSON object: `duration_s`, `sample_rate`, `channels`, `onsets_s` (seconds). Exits 1 when it cannot be read'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "follow-audio" -d 'Follow a sound\'s loudness with one servo (--servo N) or PLEN2 joint (--joint NAME): closed in silence, open at the loudest, fitted into the board\'s steps or frames within the tolerance. Servo board: writes a project with one action per step and macro 1 running them; PLEN2: a motion.json'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "probe" -d 'The connection doctor: which family answers on a port (or on every port), at which baud, what it says of itself, and how its link delivers. Sends only requests that change nothing on a servo board, a PLEN2 or an rFLEX base. Exits 1 when nothing answered'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "sim" -d 'Run an emulated board. Prints the port to connect to on the first line'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "play" -d 'Play a show with no window: connect every device (saying which answered), play the show with its sound (or silent, said) on every board together, each run\'s start, skew and end logged; Ctrl-C / SIGTERM stop every device (bases brake) and exit 130 / 143. The boards must hold the show\'s content (servo-studio import). docs/show.md'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "serve" -d 'Remote control with no window: hold every device of a show connected and take HTTP + JSON (and OSC with --osc) from cue software and control surfaces — play, stop, pose, drive (with heartbeats), status as Server-Sent Events. Loopback only unless --token-file. Ctrl-C / SIGTERM stop every device and exit 130 / 143. docs/remote.md'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "export" -d 'Read everything from a board into a project file'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "import" -d 'Write a project file onto a board: validates, backs the board up, clears it, writes, and verifies. A file with validation errors (a backup of content Servo Studio would not author) needs --force'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "gui" -d 'Open the editor window (the default with no command)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "rflex" -d 'Drive an rFLEX mobile base, or read its sensors'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "board" -d 'Board status'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "trajectory" -d 'Write what the robot outputs over time to a CSV file, one row per board update: PLEN2, one per 32.768 ms cycle from `$PM` (the frame value in tenths of a degree relative to home, before clamping); servo board, one per 10 ms (the angle in degrees). `t_ms`, then one column per joint or servo'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "convert" -d 'Convert motions from another tool (Pololu Maestro settings file, RoboPlus Motion .mtn, R+ Motion .mtnx, Blender servo-animation JSON) into a servo or PLEN2 project, or a project (or one of those files) into a Maestro settings file or Blender JSON. Prints what was converted, approximated and dropped (docs/import-export.md)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "fit" -d 'Fit a recording (the CSV `trajectory` writes: `t_ms`, then a column per joint or servo by name; PLEN2 values in tenths of a degree relative to home, servo values in degrees; any sample rate) into the fewest frames or steps whose playback on the board stays within the tolerance at every update. PLEN2: writes a motion.json; servo board: a project with one action per step and macro 1 running them in order'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and not __fish_seen_subcommand_from check ports completions man audio-info follow-audio probe sim play serve export import gui rflex board trajectory convert fit help" -f -a "help" -d 'Print this message or the help of the given subcommand(s)'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and __fish_seen_subcommand_from rflex" -f -a "status" -d 'Start the reports, wait for one full set (status, odometry on both axes, a full sonar sweep, digital I/O), print it as one JSON object, shut the reports down'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and __fish_seen_subcommand_from rflex" -f -a "drive" -d 'Release the brake, drive for a while at 10 Hz, stop, and shut down with the brake set'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and __fish_seen_subcommand_from rflex" -f -a "teleop" -d 'Drive a base from a gamepad: hold the dead-man button (the left shoulder, BTN_TL) and the left stick drives (up forward, left turns left), scaled to the robot\'s top speeds, with a dead zone. The base is stopped at once when the dead-man is released, the stick centred, the gamepad\'s events dropped (until known again) or the gamepad gone — then the brake is set and the command exits 1 — and on Ctrl-C or kill'
complete -c servo-studio -n "__fish_servo_studio_using_subcommand help; and __fish_seen_subcommand_from board" -f -a "info" -d 'Project id, memory, battery and servos'
