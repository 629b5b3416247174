#!/usr/bin/env python3
"""Records every event of the running Aseba networks to CSV, then sends one back.

The events come from aseba-mqtt (docs/mqtt.md): each robot's `emit` is
published on PREFIX/event/NAME as JSON. This script writes one CSV row per
event, and at the end publishes one event, which the bridges started with
--accept-events deliver to every robot. Needs Debian's python3-paho-mqtt.

    epuck-emu --arena default --load examples/paper-annex.aesl &
    aseba-mqtt -p examples/paper-annex.aesl --accept-events &
    examples/mqtt/record_events.py --duration 30 --csv events.csv --send bad 1
"""

import argparse
import csv
import datetime
import json
import sys
import time

import paho.mqtt.client as mqtt

COLUMNS = ["received", "time_ms", "network", "node", "node_name", "event", "args"]


def parse_command_line():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--broker", default="localhost:1883", help="HOST:PORT (default localhost:1883)")
    parser.add_argument("--prefix", default="aseba", help="the bridges' topic prefix (default aseba)")
    parser.add_argument("--csv", help="the file to write (default: standard output)")
    parser.add_argument("--duration", type=float, default=10, help="seconds to record (default 10)")
    parser.add_argument("--count", type=int, help="stop after this many events")
    parser.add_argument("--send", nargs="+", metavar=("EVENT", "ARG"),
                        help="then publish this event with these integer arguments")
    arguments = parser.parse_args()
    host, _, port = arguments.broker.rpartition(":")
    arguments.host, arguments.port = (host, int(port)) if host else (arguments.broker, 1883)
    return arguments


def main():
    arguments = parse_command_line()
    output = open(arguments.csv, "w", newline="") if arguments.csv else sys.stdout
    writer = csv.writer(output, lineterminator="\n")
    writer.writerow(COLUMNS)
    recorded = 0
    topic_start = arguments.prefix + "/event/"

    def on_connect(client, userdata, flags, code):
        if code != 0:
            sys.exit(f"record_events: the broker refused the connection ({mqtt.connack_string(code)})")
        client.subscribe(topic_start + "+", qos=1)
        print(f"recording events of {topic_start}+ on {arguments.host}:{arguments.port}",
              file=sys.stderr, flush=True)

    def on_message(client, userdata, message):
        nonlocal recorded
        try:
            event = json.loads(message.payload) if message.payload else {}
        except ValueError:
            return  # not from a bridge: not ours to record
        if isinstance(event, list):
            event = {"args": event}
        if not isinstance(event, dict):
            return
        writer.writerow([
            datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="milliseconds"),
            event.get("time_ms", ""), event.get("network", ""), event.get("node", ""),
            event.get("node_name", ""), message.topic[len(topic_start):],
            " ".join(str(value) for value in event.get("args", [])),
        ])
        output.flush()
        recorded += 1

    client = mqtt.Client()
    client.on_connect = on_connect
    client.on_message = on_message
    client.connect(arguments.host, arguments.port)
    client.loop_start()
    deadline = time.monotonic() + arguments.duration
    while time.monotonic() < deadline and (arguments.count is None or recorded < arguments.count):
        time.sleep(0.01)
    client.unsubscribe(topic_start + "+")

    if arguments.send:
        name, values = arguments.send[0], [int(value) for value in arguments.send[1:]]
        info = client.publish(topic_start + name, json.dumps({"args": values}), qos=1)
        info.wait_for_publish()
        print(f"sent {name}({', '.join(map(str, values))})", file=sys.stderr)
    client.loop_stop()
    client.disconnect()
    print(f"recorded {recorded} events", file=sys.stderr)


if __name__ == "__main__":
    main()
