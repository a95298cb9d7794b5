#include "ladarsim/sensor_model/sensor/scan_pattern.h"

#include "ladarsim/sensor_model/sensor/channel_table.h"
#include "ladarsim/sensor_model/sensor/galvo_raster.h"
#include "ladarsim/sensor_model/sensor/spinning_head.h"

namespace ladarsim::sensor_model {

std::shared_ptr<const ScanPattern> read_scan_pattern(JsonFields& scan) {
    if (!scan.has("pattern")) scan.fail("pattern", "missing: one of galvo_raster, spinning_head, channel_table");
    const std::string pattern = scan.choice("pattern", {"galvo_raster", "spinning_head", "channel_table"}, "");
    if (pattern == "galvo_raster") return GalvoRaster::read(scan);
    if (pattern == "spinning_head") return SpinningHead::read(scan);
    return ChannelTable::read(scan);
}

}  // namespace ladarsim::sensor_model
