# aseba-mqtt: Aseba networks on an MQTT broker (docs/mqtt.md), over the
# client library and libmosquitto (Debian's libmosquitto-dev).
LIBRARIES += aseba_mqtt
aseba_mqtt_SOURCES := tools/mqtt/broker_client.cpp tools/mqtt/topics.cpp tools/mqtt/payloads.cpp \
                      tools/mqtt/remote_nodes.cpp tools/mqtt/bridge.cpp
aseba_mqtt_LDLIBS := -lmosquitto -pthread

PROGRAMS += aseba-mqtt
aseba-mqtt_SOURCES := tools/mqtt/main.cpp
aseba-mqtt_LIBS := aseba_mqtt aseba_client aseba_compiler aseba_node
