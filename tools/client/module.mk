# The client library of Aseba networks: wire codec, TCP and serial links, the
# network model (nodes, descriptions, variables, execution control) and
# program loading through the compiler. Used by the `aseba` console and, later,
# by the IDE.
LIBRARIES += aseba_client
aseba_client_SOURCES := \
    tools/client/wire.cpp \
    tools/client/messages.cpp \
    tools/client/transport.cpp \
    tools/client/program.cpp \
    tools/client/variables.cpp \
    tools/client/network.cpp \
    tools/client/flasher.cpp \
    tools/client/message_text.cpp
