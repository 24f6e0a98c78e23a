#include "emulator/mcs2/properties.hpp"

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace rigsim::mcs2 {

namespace {

constexpr std::int64_t kI32Max = std::numeric_limits<std::int32_t>::max();
constexpr std::int64_t kPos = 100'000'000'000'000;   // ±100×10^12 pm or n° (4.4.10)


// Paths as the guide prints them (Table 6.3 and chapter 4's "ASCII Command" lines; the errata
// decides where they differ). Ranges and defaults from chapter 4.
constexpr std::array<Property, kPropertyCount> kTable{
    Property{Id::Cls, "*CLS", Scope::Common, Type::None, Access::W, Kind::Live, 0, 0, 0, false, false, "Table 6.1"},
    Property{Id::Ese, "*ESE", Scope::Common, Type::I32, Access::RW, Kind::Stored, 0, 255, 0, false, false, "Table 6.1"},
    Property{Id::Esr, "*ESR", Scope::Common, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, false, "Table 6.1"},
    Property{Id::Idn, "*IDN", Scope::Common, Type::String, Access::R, Kind::Live, 0, 0, 0, false, false, "Table 6.1"},
    Property{Id::Opc, "*OPC", Scope::Common, Type::None, Access::RW, Kind::Live, 0, 0, 0, false, false, "Table 6.1"},
    Property{Id::Rst, "*RST", Scope::Common, Type::None, Access::W, Kind::Live, 0, 0, 0, false, false, "Table 6.1"},
    Property{Id::Sre, "*SRE", Scope::Common, Type::I32, Access::RW, Kind::Stored, 0, 255, 0, false, false, "Table 6.1"},
    Property{Id::Stb, "*STB", Scope::Common, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, false, "Table 6.1"},
    Property{Id::Tst, "*TST", Scope::Common, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, false, "Table 6.1"},
    Property{Id::Wai, "*WAI", Scope::Common, Type::None, Access::W, Kind::Live, 0, 0, 0, false, false, "Table 6.1"},

    Property{Id::ErrCount, ":SYSTem:ERRor:COUNt", Scope::System, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, false, "6.3.8"},
    Property{Id::ErrNext, ":SYSTem:ERRor[:NEXT]", Scope::System, Type::String, Access::R, Kind::Live, 0, 0, 0, false, false, "6.3.8"},
    Property{Id::CgrOpen, ":CGRoup:OPEN", Scope::Group, Type::I32, Access::W, Kind::Live, 0, 1, 0, false, false, "6.4.1"},
    Property{Id::CgrClose, ":CGRoup:CLOSe", Scope::Group, Type::None, Access::W, Kind::Live, 0, 0, 0, false, false, "6.4.1"},
    Property{Id::CgrAbort, ":CGRoup:ABORt", Scope::Group, Type::None, Access::W, Kind::Live, 0, 0, 0, false, false, "6.4.1"},
    Property{Id::CgrFinished, ":CGRoup:FINished", Scope::Group, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, false, "6.4.1"},
    Property{Id::CgrValues, ":CGRoup:VALues", Scope::Group, Type::String, Access::R, Kind::Live, 0, 0, 0, false, false, "6.4.1"},
    Property{Id::StrOpen, ":STReam:OPEN", Scope::Stream, Type::I32, Access::W, Kind::Live, 0, 2, 0, false, false, "6.5.1"},
    Property{Id::StrFree, ":STReam:BFREe", Scope::Stream, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, false, "6.5.1"},
    Property{Id::StrFrame, ":STReam:FRAMe", Scope::Stream, Type::I64, Access::W, Kind::Live, 0, 0, 0, false, false, "6.5.1"},
    Property{Id::StrClose, ":STReam:CLOSe", Scope::Stream, Type::None, Access::W, Kind::Live, 0, 0, 0, false, false, "6.5.1"},
    Property{Id::StrAbort, ":STReam:ABORt", Scope::Stream, Type::None, Access::W, Kind::Live, 0, 0, 0, false, false, "6.5.1"},

    Property{Id::Move, ":MOVE#", Scope::Command, Type::I64, Access::W, Kind::Live, 0, 0, 0, false, true, "3.2.36"},
    Property{Id::Stop, ":STOP#", Scope::Command, Type::None, Access::W, Kind::Live, 0, 0, 0, false, true, "3.2.37"},
    Property{Id::Calibrate, ":CALibrate#", Scope::Command, Type::None, Access::W, Kind::Live, 0, 0, 0, false, true, "3.2.34"},
    Property{Id::Reference, ":REFerence#", Scope::Command, Type::None, Access::W, Kind::Live, 0, 0, 0, false, true, "3.2.35"},

    Property{Id::DevChannels, "[:PROPerty]:DEVice:NOCHannels", Scope::Device, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, false, "4.2.1"},
    Property{Id::DevModules, "[:PROPerty]:DEVice:NOBModules", Scope::Device, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, false, "4.2.2"},
    Property{Id::DevState, "[:PROPerty]:DEVice:STATe", Scope::Device, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, false, "4.2.3"},
    Property{Id::DevSerial, "[:PROPerty]:DEVice:SNUMber", Scope::Device, Type::String, Access::R, Kind::Live, 0, 0, 0, false, false, "4.2.4"},
    Property{Id::DevName, "[:PROPerty]:DEVice:NAME", Scope::Device, Type::String, Access::RW, Kind::Live, 0, 0, 0, true, false, "4.2.5"},
    Property{Id::DevEstopMode, "[:PROPerty]:DEVice:ESTop:MODE", Scope::Device, Type::I32, Access::RW, Kind::Live, 0, 2, 0, false, false, "4.2.6"},
    Property{Id::DevDiscoverMode, "[:PROPerty]:DEVice:NETWork:DISCover:MODE", Scope::Device, Type::I32, Access::RW, Kind::Stored, 0, 2, 2, true, false, "4.2.7"},
    Property{Id::DevStreamBaseRate, "[:PROPerty]:DEVice:STReaming:BASerate", Scope::Device, Type::I32, Access::RW, Kind::Stored, 10, 1000, 1000, false, false, "4.9.1"},
    Property{Id::DevStreamSyncRate, "[:PROPerty]:DEVice:STReaming:SYNCrate", Scope::Device, Type::I32, Access::RW, Kind::Stored, 1, 1000, 1, false, false, "4.9.2"},
    Property{Id::DevStreamOptions, "[:PROPerty]:DEVice:STReaming:OPTions", Scope::Device, Type::I32, Access::RW, Kind::Stored, 0, 1, 0, false, false, "4.9.3"},
    Property{Id::DevHmLock, "[:PROPerty]:DEVice:HMODule:LOPTions[:CURRent]", Scope::Device, Type::I32, Access::RW, Kind::Live, 0, 0x1f33f3, 0, false, false, "4.15.1"},
    Property{Id::DevHmLockDefault, "[:PROPerty]:DEVice:HMODule:LOPTions:DEFault", Scope::Device, Type::I32, Access::RW, Kind::Live, 0, 0x1f33f3, 0, true, false, "4.15.2"},
    Property{Id::DevTriggerMode, "[:PROPerty]:DEVice:TRIGger:INPut:MODE", Scope::Device, Type::I32, Access::RW, Kind::Live, 0, 4, 0, false, false, "4.13.1"},
    Property{Id::DevTriggerCondition, "[:PROPerty]:DEVice:TRIGger:INPut:CONDition", Scope::Device, Type::I32, Access::RW, Kind::Live, 0, 1, 0, false, false, "4.13.2"},

    Property{Id::ModPower, "[:PROPerty]:MODule#:PSUPply[:ENABled]", Scope::Module, Type::I32, Access::RW, Kind::Live, 0, 1, 1, false, true, "4.3.1"},
    Property{Id::ModState, "[:PROPerty]:MODule#:STATe", Scope::Module, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, true, "4.3.2"},
    Property{Id::ModChannels, "[:PROPerty]:MODule#:NOMChannels", Scope::Module, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, true, "4.3.3"},
    Property{Id::ModTemperature, "[:PROPerty]:MODule#:TEMPerature", Scope::Module, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, true, "4.10.3"},
    Property{Id::ModIoOptions, "[:PROPerty]:MODule#:IOModule:OPTions", Scope::Module, Type::I32, Access::RW, Kind::Live, 0, 7, 0, false, true, "4.12.1"},
    Property{Id::ModIoVoltage, "[:PROPerty]:MODule#:IOModule:VOLTage", Scope::Module, Type::I32, Access::RW, Kind::Live, 0, 1, 0, false, true, "4.12.2"},
    Property{Id::ModAinRange, "[:PROPerty]:MODule#:IOModule:AINPut:RANGe", Scope::Module, Type::I32, Access::RW, Kind::Live, 0, 4, 0, true, true, "4.12.3"},
    Property{Id::ModDin, "[:PROPerty]:MODule#:AUXiliary:DINPut[:VALue]", Scope::Module, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, true, "4.11.7"},
    Property{Id::ModDout, "[:PROPerty]:MODule#:AUXiliary:DOUTput[:VALue]", Scope::Module, Type::I32, Access::RW, Kind::Live, 0, 15, 0, false, true, "4.11.8"},
    Property{Id::ModDoutSet, "[:PROPerty]:MODule#:AUXiliary:DOUTput:SET", Scope::Module, Type::I32, Access::W, Kind::Live, 0, 15, 0, false, true, "4.11.8"},
    Property{Id::ModDoutClear, "[:PROPerty]:MODule#:AUXiliary:DOUTput:CLEar", Scope::Module, Type::I32, Access::W, Kind::Live, 0, 15, 0, false, true, "4.11.8"},
    Property{Id::ModAout, "[:PROPerty]:MODule#:AUXiliary:AOUTput:VALue#", Scope::Module, Type::I32, Access::RW, Kind::Live, -32768, 32767, 0, false, true, "4.11.9"},

    Property{Id::Amplifier, "[:PROPerty]:CHANnel#:AMPLifier[:ENABled]", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 1, 1, false, true, "4.4.1"},
    Property{Id::ControlOptions, "[:PROPerty]:CHANnel#:PCONtrol:OPTions", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 0x3f, 0, true, true, "4.4.2"},
    Property{Id::ActuatorMode, "[:PROPerty]:CHANnel#:ACTuator:MODE", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 2, 0, false, false, "4.4.3"},
    Property{Id::LoopInput, "[:PROPerty]:CHANnel#:CLINput[:SELect]", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 2, 1, true, true, "4.4.4"},
    Property{Id::SensorInputSelect, "[:PROPerty]:CHANnel#:CLINput:SENSor:SELect", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 1, 0, true, true, "4.4.5"},
    Property{Id::SensorValue, "[:PROPerty]:CHANnel#:CLINput:SENSor[:VALue]", Scope::Channel, Type::I64, Access::R, Kind::Live, 0, 0, 0, false, true, "4.4.27"},
    Property{Id::AuxValue, "[:PROPerty]:CHANnel#:CLINput:AUXiliary[:VALue]", Scope::Channel, Type::I64, Access::R, Kind::Live, 0, 0, 0, false, true, "4.4.28"},
    Property{Id::PositionerType, "[:PROPerty]:CHANnel#:PTYPe[:CODE]", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, kI32Max, 300, true, true, "4.4.6"},
    Property{Id::PositionerTypeName, "[:PROPerty]:CHANnel#:PTYPe:NAME", Scope::Channel, Type::String, Access::R, Kind::Live, 0, 0, 0, false, false, "4.4.7"},
    Property{Id::MoveMode, "[:PROPerty]:CHANnel#:MMODe", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 4, 0, false, true, "4.4.8"},
    Property{Id::State, "[:PROPerty]:CHANnel#:STATe", Scope::Channel, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, true, "4.4.9"},
    Property{Id::Position, "[:PROPerty]:CHANnel#:POSition[:CURRent]", Scope::Channel, Type::I64, Access::RW, Kind::Live, -kPos, kPos, 0, false, true, "4.4.10"},
    Property{Id::TargetPosition, "[:PROPerty]:CHANnel#:POSition:TARGet", Scope::Channel, Type::I64, Access::R, Kind::Live, 0, 0, 0, false, true, "4.4.11"},
    Property{Id::ScanPosition, "[:PROPerty]:CHANnel#:POSition:SCAN", Scope::Channel, Type::I64, Access::R, Kind::Live, 0, 0, 0, false, true, "4.4.12"},
    Property{Id::MeanShift, "[:PROPerty]:CHANnel#:POSition:MSHift", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 7, 5, true, true, "4.4.25"},
    Property{Id::ScanVelocity, "[:PROPerty]:CHANnel#:SCAN:VELocity", Scope::Channel, Type::I64, Access::RW, Kind::Stored, 1, 65'535'000'000, 65535, false, true, "4.4.13"},
    Property{Id::HoldTime, "[:PROPerty]:CHANnel#:HOLDtime", Scope::Channel, Type::I32, Access::RW, Kind::Live, -1, kInfinite, kInfinite, false, true, "4.4.14"},
    Property{Id::Velocity, "[:PROPerty]:CHANnel#:VELocity", Scope::Channel, Type::I64, Access::RW, Kind::Live, 0, 100'000'000'000, 0, false, true, "4.4.15"},
    Property{Id::Acceleration, "[:PROPerty]:CHANnel#:ACCeleration", Scope::Channel, Type::I64, Access::RW, Kind::Live, 0, 10'000'000'000'000, 0, false, true, "4.4.16"},
    Property{Id::MaxFrequency, "[:PROPerty]:CHANnel#:MCLFrequency[:CURRent]", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 50, 20000, 18500, false, true, "4.4.17"},
    Property{Id::MaxFrequencyDefault, "[:PROPerty]:CHANnel#:MCLFrequency:DEFault", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 50, 20000, 18500, true, true, "4.4.18"},
    Property{Id::StepFrequency, "[:PROPerty]:CHANnel#:STEP:FREQuency", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 1, 20000, 1000, false, true, "4.4.19"},
    Property{Id::StepAmplitude, "[:PROPerty]:CHANnel#:STEP:AMPLitude", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 1, 65535, 65535, false, true, "4.4.20"},
    Property{Id::FollowingErrorLimit, "[:PROPerty]:CHANnel#:FELimit", Scope::Channel, Type::I64, Access::RW, Kind::Stored, 0, kPos, 0, true, true, "4.4.21"},
    Property{Id::BroadcastStop, "[:PROPerty]:CHANnel#:BSTop:OPTions", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 7, 0, false, true, "4.4.22"},
    Property{Id::SensorPowerMode, "[:PROPerty]:CHANnel#:SENSor:PMODe", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 2, 1, true, true, "4.4.23"},
    Property{Id::PowerSaveDelay, "[:PROPerty]:CHANnel#:SENSor:PSDelay", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 5000, 100, true, true, "4.4.24"},
    Property{Id::SafeDirection, "[:PROPerty]:CHANnel#:SDIRection", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 1, 0, true, true, "4.4.26"},
    Property{Id::TtzThreshold, "[:PROPerty]:CHANnel#:TTZVoltage:THReshold[:HOLD]", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 10'000'000, 0, true, true, "4.4.29"},
    Property{Id::ScaleOffset, "[:PROPerty]:CHANnel#:LSCale:OFFset", Scope::Channel, Type::I64, Access::RW, Kind::Live, -kPos, kPos, 0, true, true, "4.5.1"},
    Property{Id::ScaleInversion, "[:PROPerty]:CHANnel#:LSCale:INVersion", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 1, 0, true, true, "4.5.2"},
    Property{Id::RangeMin, "[:PROPerty]:CHANnel#:RLIMit:MIN", Scope::Channel, Type::I64, Access::RW, Kind::Stored, -kPos, kPos, 0, false, true, "4.5.3"},
    Property{Id::RangeMax, "[:PROPerty]:CHANnel#:RLIMit:MAX", Scope::Channel, Type::I64, Access::RW, Kind::Stored, -kPos, kPos, 0, false, true, "4.5.4"},
    Property{Id::CalibrationOptions, "[:PROPerty]:CHANnel#:CALibration:OPTions", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 0x107, 0, false, true, "4.6.1"},
    Property{Id::CorrectionOptions, "[:PROPerty]:CHANnel#:SCORrection:OPTions", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 0x1f, 0x0f, true, true, "4.6.2"},
    Property{Id::ReferencingOptions, "[:PROPerty]:CHANnel#:REFerencing:OPTions", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 0x3f, 0, false, true, "4.7.1"},
    Property{Id::DistanceToMark, "[:PROPerty]:CHANnel#:REFerencing:DTRMark", Scope::Channel, Type::I64, Access::R, Kind::Live, 0, 0, 0, false, true, "4.7.2"},
    Property{Id::DistanceCodeInverted, "[:PROPerty]:CHANnel#:REFerencing:DCINverted", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 1, 0, true, true, "4.7.3"},
    Property{Id::ChannelError, "[:PROPerty]:CHANnel#:ERRor", Scope::Channel, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, true, "4.10.1"},
    Property{Id::ChannelTemperature, "[:PROPerty]:CHANnel#:TEMPerature", Scope::Channel, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, true, "4.10.2"},
    Property{Id::TriggerMode, "[:PROPerty]:CHANnel#:TRIGger:OUTPut:MODE", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 3, 0, false, true, "4.14.1"},
    Property{Id::TriggerPolarity, "[:PROPerty]:CHANnel#:TRIGger:OUTPut:POLarity", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 1, 1, false, true, "4.14.2"},
    Property{Id::TriggerPulseWidth, "[:PROPerty]:CHANnel#:TRIGger:OUTPut:PWIDth", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 100, 4'000'000'000, 1000, false, true, "4.14.3"},
    Property{Id::CompareThreshold, "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:THReshold[:STARt]", Scope::Channel, Type::I64, Access::RW, Kind::Stored, -kPos, kPos, 1'000'000'000, false, true, "4.14.4"},
    Property{Id::CompareIncrement, "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:INCRement", Scope::Channel, Type::I64, Access::RW, Kind::Stored, 1, 1'000'000'000'000, 1'000'000'000, false, true, "4.14.5"},
    Property{Id::CompareDirection, "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:DIRection", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 2, 0, false, true, "4.14.6"},
    Property{Id::CompareLimitMin, "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:LMIN", Scope::Channel, Type::I64, Access::RW, Kind::Stored, -kPos, kPos, 0, false, true, "4.14.7"},
    Property{Id::CompareLimitMax, "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:LMAX", Scope::Channel, Type::I64, Access::RW, Kind::Stored, -kPos, kPos, 0, false, true, "4.14.8"},
    Property{Id::AuxPositionerType, "[:PROPerty]:CHANnel#:AUXiliary:PTYPe", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 250, 253, 250, true, true, "4.11.1"},
    Property{Id::AuxPositionerTypeName, "[:PROPerty]:CHANnel#:AUXiliary:PTName", Scope::Channel, Type::String, Access::R, Kind::Live, 0, 0, 0, false, false, "4.11.2"},
    Property{Id::AuxInputSelect, "[:PROPerty]:CHANnel#:AUXiliary:ISELect", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 1, 0, true, true, "4.11.3"},
    Property{Id::AuxInputIndex, "[:PROPerty]:CHANnel#:AUXiliary:IOModule:INPut:INDex", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 1, 0, true, true, "4.11.4"},
    Property{Id::AuxInputValue, "[:PROPerty]:CHANnel#:AUXiliary:IOModule:INPut:VALue#", Scope::Channel, Type::I64, Access::R, Kind::Live, 0, 0, 0, false, true, "4.11.6"},
    Property{Id::AuxDirectionInversion, "[:PROPerty]:CHANnel#:AUXiliary:DINVersion", Scope::Channel, Type::I32, Access::RW, Kind::Stored, 0, 1, 0, true, true, "4.11.5"},

    Property{Id::TunMovementType, "[:PROPerty]:CHANnel#:TUNing:MTYPe", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 3, 0, false, true, "4.8.1"},
    Property{Id::TunCustom, "[:PROPerty]:CHANnel#:TUNing:CUSTom", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 1, 0, false, true, "4.8.2"},
    Property{Id::TunBaseUnit, "[:PROPerty]:CHANnel#:TUNing:BASE:UNIT", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 2, 3, 2, false, true, "4.8.3"},
    Property{Id::TunBaseResolution, "[:PROPerty]:CHANnel#:TUNing:BASE:RESolution", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, -12, 0, -12, false, true, "4.8.4"},
    Property{Id::TunHeadType, "[:PROPerty]:CHANnel#:TUNing:HTYPe", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 3, 0, false, true, "4.8.5"},
    Property{Id::TunReferenceType, "[:PROPerty]:CHANnel#:TUNing:RTYPe", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 3, 2, false, true, "4.8.6"},
    Property{Id::TunGainP, "[:PROPerty]:CHANnel#:TUNing:GAIN:P", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 2'000'000'000, 1000, false, true, "4.8.7"},
    Property{Id::TunGainI, "[:PROPerty]:CHANnel#:TUNing:GAIN:I", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 2'000'000'000, 0, false, true, "4.8.8"},
    Property{Id::TunGainD, "[:PROPerty]:CHANnel#:TUNing:GAIN:D", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 2'000'000'000, 0, false, true, "4.8.9"},
    Property{Id::TunGainShift, "[:PROPerty]:CHANnel#:TUNing:GAIN:SHIFt", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 16, 10, false, true, "4.8.10"},
    Property{Id::TunAntiWindup, "[:PROPerty]:CHANnel#:TUNing:AWINdup", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 2'000'000'000, 0, false, true, "4.8.11"},
    Property{Id::TunEsdDistance, "[:PROPerty]:CHANnel#:TUNing:ESDetection:DISTance", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 1'000'000'000, 100'000'000, false, true, "4.8.12"},
    Property{Id::TunEsdCounter, "[:PROPerty]:CHANnel#:TUNing:ESDetection:COUNter", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 1, 4'000'000'000, 1000, false, true, "4.8.13"},
    Property{Id::TunTargetReached, "[:PROPerty]:CHANnel#:TUNing:THReshold:TREached", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 1'000'000, 0, false, true, "4.8.14"},
    Property{Id::TunTargetHold, "[:PROPerty]:CHANnel#:TUNing:THReshold:THOLd", Scope::Channel, Type::I32, Access::Tuning, Kind::Live, 0, 1'000'000, 0, false, true, "4.8.15"},
    Property{Id::TunSave, "[:PROPerty]:CHANnel#:TUNing:SAVE", Scope::Channel, Type::I32, Access::W, Kind::Live, 250, 253, 0, true, true, "4.8.16"},
    Property{Id::TunWriteProtection, "[:PROPerty]:CHANnel#:TUNing:WPRotection", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, kI32Max, 1, false, true, "4.8.17"},

    Property{Id::SensorModeAlias, "[:PROPerty]:CHANnel#:SENSor:MODE", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 2, 1, true, true, "later firmware"},
    Property{Id::SensorDelayAlias, "[:PROPerty]:CHANnel#:SENSor:DELay", Scope::Channel, Type::I32, Access::RW, Kind::Live, 0, 5000, 100, true, true, "later firmware"},
    Property{Id::ModuleStateAlias, "[:PROPerty]:MODule:STATe", Scope::Device, Type::I32, Access::R, Kind::Live, 0, 0, 0, false, true, "later firmware"},
    Property{Id::FollowingError, "[:PROPerty]:CHANnel#:FERRor", Scope::Channel, Type::I64, Access::R, Kind::Live, 0, 0, 0, false, true, "later firmware"},
};

static_assert(kTable.size() == kPropertyCount);

constexpr bool in_id_order()
{
    for (std::size_t i = 0; i < kTable.size(); ++i)
        if (static_cast<std::size_t>(kTable[i].id) != i)
            return false;
    return true;
}
static_assert(in_id_order(), "the table's rows are in Id order");

struct Tree {
    CommandTree tree;
    std::vector<const Property*> of_node;
};

std::vector<std::string_view> paths()
{
    std::vector<std::string_view> out;
    for (const auto& p : kTable)
        out.push_back(p.path);
    return out;
}

const Tree& the_tree()
{
    static const Tree t = [] {
        Tree out{CommandTree(paths()), {}};
        out.of_node.assign(out.tree.size(), nullptr);
        for (std::size_t i = 0; i < kTable.size(); ++i)
            out.of_node[static_cast<std::size_t>(out.tree.node_of_path(i))] = &kTable[i];
        return out;
    }();
    return t;
}

} // namespace

const std::array<Property, kPropertyCount>& table()
{
    return kTable;
}

const CommandTree& command_tree()
{
    return the_tree().tree;
}

const Property* node_property(int node)
{
    const auto& of = the_tree().of_node;
    return node >= 0 && static_cast<std::size_t>(node) < of.size() ? of[static_cast<std::size_t>(node)] : nullptr;
}

} // namespace rigsim::mcs2
