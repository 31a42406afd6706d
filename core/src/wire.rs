//! Fixed-size wire types shared by the flight service, the feeder and the firmware.
