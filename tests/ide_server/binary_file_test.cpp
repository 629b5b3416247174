// .abo files and the description fingerprint, against the reference Aseba
// (libasebacommon: TargetDescription::crc and crcXModem) and aesl.md §6.

#include <gtest/gtest.h>

#include <aseba/common/msg/TargetDescription.h>
#include <aseba/common/utils/utils.h>

#include "tools/compiler/target_presets.hpp"
#include "tools/ide/binary_file.hpp"

namespace
{

using aseba::TargetDescription;

Aseba::TargetDescription reference_description(const TargetDescription &ours)
{
    Aseba::TargetDescription reference;
    reference.name = Aseba::UTF8ToWString(ours.name);
    reference.protocolVersion = ours.protocol_version;
    reference.bytecodeSize = ours.bytecode_size;
    reference.variablesSize = ours.variables_size;
    reference.stackSize = ours.stack_size;
    for (const auto &variable : ours.named_variables)
        reference.namedVariables.emplace_back(Aseba::UTF8ToWString(variable.name), variable.size);
    for (const auto &event : ours.local_events)
        reference.localEvents.push_back(
          { Aseba::UTF8ToWString(event.name), Aseba::UTF8ToWString(event.description) });
    for (const auto &function : ours.native_functions) {
        Aseba::TargetDescription::NativeFunction native;
        native.name = Aseba::UTF8ToWString(function.name);
        native.description = Aseba::UTF8ToWString(function.description);
        for (const auto &parameter : function.parameters)
            native.parameters.emplace_back(Aseba::UTF8ToWString(parameter.name), parameter.size);
        reference.nativeFunctions.push_back(native);
    }
    return reference;
}

uint16_t word_at(const std::vector<uint8_t> &bytes, size_t offset)
{
    return uint16_t(bytes.at(offset) | bytes.at(offset + 1) << 8);
}

TEST(BinaryFile, TheFingerprintIsTheReferences)
{
    for (const TargetDescription &description : { aseba::epuck_target(), aseba::dummy_target() }) {
        EXPECT_EQ(aseba::ide::description_fingerprint(description),
                  reference_description(description).crc())
          << description.name;
    }
}

TEST(BinaryFile, TheFieldsAreWhereAeslMdPlacesThem)
{
    TargetDescription description = aseba::epuck_target();
    std::vector<uint16_t> bytecode = { 3, 0x0001, 0x1002, 0xFFFF };
    aseba::ide::BinaryIdentity identity{ 7, 0x1234, 0x0009 };
    std::vector<uint8_t> bytes = aseba::ide::binary_file(description, identity, bytecode);

    ASSERT_EQ(bytes.size(), 20 + 2 * bytecode.size() + 2);
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), std::string("ABO\0", 4));
    EXPECT_EQ(word_at(bytes, 4), 0);      // format version
    EXPECT_EQ(word_at(bytes, 6), 5);      // protocol
    EXPECT_EQ(word_at(bytes, 8), 0x1234); // product id
    EXPECT_EQ(word_at(bytes, 10), 9);     // firmware version
    EXPECT_EQ(word_at(bytes, 12), 7);     // node id
    EXPECT_EQ(word_at(bytes, 14), Aseba::crcXModem(0, Aseba::UTF8ToWString(description.name)));
    EXPECT_EQ(word_at(bytes, 16), reference_description(description).crc());
    EXPECT_EQ(word_at(bytes, 18), bytecode.size());
    uint16_t crc = 0;
    for (size_t i = 0; i < bytecode.size(); i++) {
        EXPECT_EQ(word_at(bytes, 20 + 2 * i), bytecode[i]);
        crc = Aseba::crcXModem(crc, bytecode[i]);
    }
    EXPECT_EQ(word_at(bytes, 20 + 2 * bytecode.size()), crc);
}

TEST(BinaryFile, Base64IsRfc4648s)
{
    auto encode = [](const std::string &text) {
        return aseba::ide::base64(std::vector<uint8_t>(text.begin(), text.end()));
    };
    // RFC 4648 §10.
    EXPECT_EQ(encode(""), "");
    EXPECT_EQ(encode("f"), "Zg==");
    EXPECT_EQ(encode("fo"), "Zm8=");
    EXPECT_EQ(encode("foo"), "Zm9v");
    EXPECT_EQ(encode("foob"), "Zm9vYg==");
    EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
    EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
    EXPECT_EQ(aseba::ide::base64({ 0xFB, 0xFF }), "+/8=");
}

} // namespace
