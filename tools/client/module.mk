# The client library of Aseba networks: wire codec, TCP and serial links, the
# network model (nodes, descriptions, variables, execution control) and
# program loading through the compiler. Used by the `aseba` console and, later,
# by the IDE.
LIBRARIES += aseba_client
aseba_client_SOURCES := \
    tools/client/wire.cpp \
    tools/client/messages.cpp \
    tools/client/byte_stream.cpp \
    tools/client/transport.cpp \
    tools/client/program.cpp \
    tools/client/variables.cpp \
    tools/client/network.cpp \
    tools/client/network_links.cpp \
    tools/client/flasher.cpp \
    tools/client/message_text.cpp \
    tools/client/terminal_text.cpp
# Links over standalone asio (Debian libasio-dev, header only), kept out of
# the library's public headers; its resolver runs in a thread of its own.
aseba_client_LDLIBS := -pthread
