# Tests of the MQTT bridge: its payloads, topics and id remapping as data
# (mqtt_units_test), and aseba-mqtt end to end with Debian's mosquitto and
# epuck-emu, both started on free loopback ports (mqtt_bridge_test).
TESTS += mqtt_units_test
mqtt_units_test_SOURCES := tests/mqtt/payloads_test.cpp tests/mqtt/remote_nodes_test.cpp
mqtt_units_test_LIBS := aseba_mqtt aseba_client aseba_compiler aseba_node
mqtt_units_test_LDLIBS := -lgtest -lgtest_main -pthread

TESTS += mqtt_bridge_test
mqtt_bridge_test_SOURCES := tests/mqtt/bridge_test.cpp tests/mqtt/mqtt_support.cpp \
                            tests/console/console_support.cpp
mqtt_bridge_test_LIBS := aseba_mqtt aseba_client aseba_compiler aseba_node
mqtt_bridge_test_LDLIBS := -lgtest -lgtest_main -pthread

# The test starts these programs of its own build (order-only: run, not linked).
$(foreach v,$(VARIANTS),$(eval \
  $(BUILD)/$(v)/tests/mqtt_bridge_test: | $(BUILD)/$(v)/bin/epuck-emu $(BUILD)/$(v)/bin/aseba-mqtt))
