// UDP datagrams out of hand-made captures: whole, in IPv4 fragments in any order, and clear
// errors for files that are not captures or that the capture cut short.
#include <catch2/catch.hpp>

#include <fstream>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/pcap_udp.h"
#include "../support/pcap_writer.h"
#include "../support/scratch_dir.h"
#include "../support/udp_datagrams.h"

using namespace ladarsim;
using namespace ladarsim;
using test::Bytes;
using test::PcapRecord;
using test::datagrams;

namespace {

Bytes counting(std::size_t size) {
    Bytes b(size);
    for (std::size_t i = 0; i < size; ++i) b[i] = static_cast<unsigned char>(i * 7 + i / 251);
    return b;
}

std::vector<PcapRecord> records(const std::vector<Bytes>& frames, std::uint32_t first_second = 100) {
    std::vector<PcapRecord> r;
    for (const Bytes& f : frames) r.push_back({first_second, static_cast<std::uint32_t>(r.size()), f});
    return r;
}

}  // namespace

TEST_CASE("a datagram within the MTU arrives whole, with its port and capture time", "[pcap_udp]") {
    const test::ScratchDir dir;
    const Bytes payload = counting(1206);
    const auto frames = test::udp_fragments(payload, 2368, 1);
    REQUIRE(frames.size() == 1);
    test::write_pcap(dir / "one.pcap", {{1700000000, 250000, frames[0]}});
    const auto seen = datagrams(dir / "one.pcap");
    REQUIRE(seen.size() == 1);
    CHECK(seen[0].record == 1);
    CHECK(seen[0].time_s == Approx(1700000000.25).margin(1e-6));
    CHECK(seen[0].port == 2368);
    CHECK(seen[0].payload == payload);
}

TEST_CASE("a datagram larger than the MTU is reassembled from its fragments, whatever their order", "[pcap_udp]") {
    const test::ScratchDir dir;
    const Bytes big = counting(24832), small = counting(48);
    auto fragments = test::udp_fragments(big, 7502, 9);
    REQUIRE(fragments.size() == 17);  // 24,840 bytes of UDP in 1,480-byte pieces
    // Reversed, with a duplicate and another datagram in between: still one datagram, once.
    std::vector<Bytes> sent(fragments.rbegin(), fragments.rend());
    sent.insert(sent.begin() + 5, test::udp_fragments(small, 7503, 10)[0]);
    sent.insert(sent.begin() + 8, fragments[3]);
    test::write_pcap(dir / "fragments.pcap", records(sent));
    const auto seen = datagrams(dir / "fragments.pcap");
    REQUIRE(seen.size() == 2);
    CHECK(seen[0].port == 7503);
    CHECK(seen[0].payload == small);
    CHECK(seen[1].port == 7502);
    CHECK(seen[1].payload == big);
    CHECK(seen[1].record == sent.size());  // completed by the last fragment to arrive
}

TEST_CASE("a datagram missing a fragment is never visited, nor patched up by a later one of the same id", "[pcap_udp]") {
    // IPv4 identifications come round again: a later datagram that lost a different fragment
    // must not complete an old one with its own bytes.
    const test::ScratchDir dir;
    const Bytes old_one = counting(5000), new_one(5000, 0x55), other = counting(300);
    auto old_fragments = test::udp_fragments(old_one, 7502, 3), new_fragments = test::udp_fragments(new_one, 7502, 3);
    old_fragments.erase(old_fragments.begin() + 1);
    new_fragments.erase(new_fragments.begin() + 2);
    new_fragments.push_back(test::udp_fragments(other, 7502, 4)[0]);
    std::vector<PcapRecord> r = records(old_fragments, 100);
    for (const PcapRecord& later : records(new_fragments, 200)) r.push_back(later);
    test::write_pcap(dir / "lost.pcap", r);
    const auto seen = datagrams(dir / "lost.pcap");
    REQUIRE(seen.size() == 1);
    CHECK(seen[0].payload == other);
}

TEST_CASE("what is not a capture of UDP over Ethernet, or was cut short, is one InputError", "[pcap_udp]") {
    const test::ScratchDir dir;
    auto fails = [&](const std::filesystem::path& file) {
        CHECK_THROWS_AS(for_each_udp_datagram(file, [](const UdpDatagram&) {}), InputError);
    };
    std::ofstream(dir / "text.pcap") << "not a capture at all, just text";
    fails(dir / "text.pcap");
    fails(dir / "none.pcap");
    const Bytes frame = test::udp_fragments(counting(100), 7502, 1)[0];
    test::write_pcap(dir / "raw_ip.pcap", {{1, 0, frame}}, 101);  // link type: raw IP, not Ethernet
    fails(dir / "raw_ip.pcap");
    test::write_pcap(dir / "snapped.pcap", {{1, 0, Bytes(frame.begin(), frame.begin() + 60), static_cast<std::uint32_t>(frame.size())}});
    fails(dir / "snapped.pcap");
    test::write_pcap(dir / "whole.pcap", {{1, 0, frame}});
    std::filesystem::resize_file(dir / "whole.pcap", std::filesystem::file_size(dir / "whole.pcap") - 10);
    fails(dir / "whole.pcap");
}

TEST_CASE("a packet whose IPv4 header claims more than the wire carried is skipped", "[pcap_udp]") {
    // A VLP-16's position packets say 1234 bytes of IPv4 and carry 540.
    const test::ScratchDir dir;
    const Bytes frame = test::udp_fragments(counting(100), 8308, 1)[0];
    Bytes liar = frame;
    liar[16] = 0x04, liar[17] = 0xD2;
    test::write_pcap(dir / "liar.pcap", {{1, 0, liar}, {1, 1, frame}});
    const auto seen = datagrams(dir / "liar.pcap");
    REQUIRE(seen.size() == 1);
    CHECK(seen[0].record == 2);
}
