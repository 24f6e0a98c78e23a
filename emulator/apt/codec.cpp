#include "emulator/apt/codec.hpp"

namespace rigsim::apt::msg {

namespace {

/// Reads the fields of a data packet in wire order (the caller checked the length).
struct Reader {
    std::string_view in;
    std::size_t pos = 0;

    void get(std::uint8_t& v) { v = get_u8(in, pos++); }
    void get(std::uint16_t& v) { v = get_u16(in, pos), pos += 2; }
    void get(std::int16_t& v) { v = get_i16(in, pos), pos += 2; }
    void get(std::uint32_t& v) { v = get_u32(in, pos), pos += 4; }
    void get(std::int32_t& v) { v = get_i32(in, pos), pos += 4; }
    template <std::size_t N> void get(std::array<char, N>& v)
    {
        in.copy(v.data(), N, pos);
        pos += N;
    }
    void get(std::optional<std::int32_t>& v)
    {
        std::int32_t d = 0;
        get(d);
        v = d;
    }
    void get(MotorStatus& v)
    {
        DcStatus s;
        std::apply([&](auto&... f) { (get(f), ...); }, DcStatus::fields(s));
        v = s;
    }
};

/// The data packet length of message T in its long form.
template <class T> std::size_t data_size()
{
    if constexpr (std::is_same_v<T, MoveRelative> || std::is_same_v<T, MoveAbsolute>)
        return encode_data(T{1, 0}).size();
    else
        return encode_data(T{}).size();
}

Message untyped(const Frame& f)
{
    return Untyped{f.id, f.param1, f.param2, f.has_data, std::string(f.data)};
}

/// Frame `f` as message T: from its data packet, or from param1 and param2 of its header.
template <class T> Message as(const Frame& f)
{
    T m{};
    if constexpr (std::is_same_v<T, MoveRelative> || std::is_same_v<T, MoveAbsolute>) {
        if (!f.has_data) {
            m.chan_ident = f.param1;
            return m;
        }
    } else if constexpr (T::header_only) {
        if (f.has_data)
            return untyped(f);
        const std::uint8_t params[2] = {f.param1, f.param2};
        std::size_t i = 0;
        std::apply([&](auto&... field) { ((field = params[i++]), ...); }, T::fields(m));
        return m;
    }
    if (!f.has_data || f.data.size() != data_size<T>())
        return untyped(f);
    Reader r{f.data};
    std::apply([&](auto&... field) { (r.get(field), ...); }, T::fields(m));
    return m;
}

/// Generic System Control Messages (p. 15-26).
std::optional<Message> decode_generic(const Frame& f)
{
    switch (f.id) {
    case MGMSG_MOD_IDENTIFY: return as<ModIdentify>(f);
    case MGMSG_MOD_SET_CHANENABLESTATE: return as<ModSetChanEnableState>(f);
    case MGMSG_MOD_REQ_CHANENABLESTATE: return as<ModReqChanEnableState>(f);
    case MGMSG_MOD_GET_CHANENABLESTATE: return as<ModGetChanEnableState>(f);
    case MGMSG_HW_DISCONNECT: return as<HwDisconnect>(f);
    case MGMSG_HW_RESPONSE: return as<HwResponse>(f);
    case MGMSG_HW_RICHRESPONSE: return as<HwRichResponse>(f);
    case MGMSG_HW_START_UPDATEMSGS: return as<HwStartUpdateMsgs>(f);
    case MGMSG_HW_STOP_UPDATEMSGS: return as<HwStopUpdateMsgs>(f);
    case MGMSG_HW_REQ_INFO: return as<HwReqInfo>(f);
    case MGMSG_HW_GET_INFO: return as<HwGetInfo>(f);
    case MGMSG_RACK_REQ_BAYUSED: return as<RackReqBayUsed>(f);
    case MGMSG_RACK_GET_BAYUSED: return as<RackGetBayUsed>(f);
    case MGMSG_HUB_REQ_BAYUSED: return as<HubReqBayUsed>(f);
    case MGMSG_HUB_GET_BAYUSED: return as<HubGetBayUsed>(f);
    case MGMSG_RACK_REQ_STATUSBITS: return as<RackReqStatusBits>(f);
    case MGMSG_RACK_GET_STATUSBITS: return as<RackGetStatusBits>(f);
    case MGMSG_RACK_SET_DIGOUTPUTS: return as<RackSetDigOutputs>(f);
    case MGMSG_RACK_REQ_DIGOUTPUTS: return as<RackReqDigOutputs>(f);
    case MGMSG_RACK_GET_DIGOUTPUTS: return as<RackGetDigOutputs>(f);
    case MGMSG_HW_YES_FLASH_PROGRAMMING: return as<HwYesFlashProgramming>(f);
    case MGMSG_HW_NO_FLASH_PROGRAMMING: return as<HwNoFlashProgramming>(f);
    default:
        return std::nullopt;
    }
}

/// The motor parameter trios (p. 27-60).
std::optional<Message> decode_trio(const Frame& f)
{
    switch (f.id) {
    case MGMSG_MOT_SET_POSCOUNTER: return as<SetPosCounter>(f);
    case MGMSG_MOT_REQ_POSCOUNTER: return as<ReqPosCounter>(f);
    case MGMSG_MOT_GET_POSCOUNTER: return as<GetPosCounter>(f);
    case MGMSG_MOT_SET_ENCCOUNTER: return as<SetEncCounter>(f);
    case MGMSG_MOT_REQ_ENCCOUNTER: return as<ReqEncCounter>(f);
    case MGMSG_MOT_GET_ENCCOUNTER: return as<GetEncCounter>(f);
    case MGMSG_MOT_SET_VELPARAMS: return as<SetVelParams>(f);
    case MGMSG_MOT_REQ_VELPARAMS: return as<ReqVelParams>(f);
    case MGMSG_MOT_GET_VELPARAMS: return as<GetVelParams>(f);
    case MGMSG_MOT_SET_JOGPARAMS: return as<SetJogParams>(f);
    case MGMSG_MOT_REQ_JOGPARAMS: return as<ReqJogParams>(f);
    case MGMSG_MOT_GET_JOGPARAMS: return as<GetJogParams>(f);
    case MGMSG_MOT_SET_GENMOVEPARAMS: return as<SetGenMoveParams>(f);
    case MGMSG_MOT_REQ_GENMOVEPARAMS: return as<ReqGenMoveParams>(f);
    case MGMSG_MOT_GET_GENMOVEPARAMS: return as<GetGenMoveParams>(f);
    case MGMSG_MOT_SET_MOVERELPARAMS: return as<SetMoveRelParams>(f);
    case MGMSG_MOT_REQ_MOVERELPARAMS: return as<ReqMoveRelParams>(f);
    case MGMSG_MOT_GET_MOVERELPARAMS: return as<GetMoveRelParams>(f);
    case MGMSG_MOT_SET_MOVEABSPARAMS: return as<SetMoveAbsParams>(f);
    case MGMSG_MOT_REQ_MOVEABSPARAMS: return as<ReqMoveAbsParams>(f);
    case MGMSG_MOT_GET_MOVEABSPARAMS: return as<GetMoveAbsParams>(f);
    case MGMSG_MOT_SET_HOMEPARAMS: return as<SetHomeParams>(f);
    case MGMSG_MOT_REQ_HOMEPARAMS: return as<ReqHomeParams>(f);
    case MGMSG_MOT_GET_HOMEPARAMS: return as<GetHomeParams>(f);
    case MGMSG_MOT_SET_LIMSWITCHPARAMS: return as<SetLimSwitchParams>(f);
    case MGMSG_MOT_REQ_LIMSWITCHPARAMS: return as<ReqLimSwitchParams>(f);
    case MGMSG_MOT_GET_LIMSWITCHPARAMS: return as<GetLimSwitchParams>(f);
    case MGMSG_MOT_SET_DCPIDPARAMS: return as<SetDcPidParams>(f);
    case MGMSG_MOT_REQ_DCPIDPARAMS: return as<ReqDcPidParams>(f);
    case MGMSG_MOT_GET_DCPIDPARAMS: return as<GetDcPidParams>(f);
    case MGMSG_MOT_SET_AVMODES: return as<SetAvModes>(f);
    case MGMSG_MOT_REQ_AVMODES: return as<ReqAvModes>(f);
    case MGMSG_MOT_GET_AVMODES: return as<GetAvModes>(f);
    case MGMSG_MOT_SET_POTPARAMS: return as<SetPotParams>(f);
    case MGMSG_MOT_REQ_POTPARAMS: return as<ReqPotParams>(f);
    case MGMSG_MOT_GET_POTPARAMS: return as<GetPotParams>(f);
    case MGMSG_MOT_SET_BUTTONPARAMS: return as<SetButtonParams>(f);
    case MGMSG_MOT_REQ_BUTTONPARAMS: return as<ReqButtonParams>(f);
    case MGMSG_MOT_GET_BUTTONPARAMS: return as<GetButtonParams>(f);
    default:
        return std::nullopt;
    }
}

/// The brushless (PMD) parameter trios (p. 61-76).
std::optional<Message> decode_pmd_trio(const Frame& f)
{
    switch (f.id) {
    case MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS: return as<SetPmdPositionLoopParams>(f);
    case MGMSG_MOT_REQ_PMDPOSITIONLOOPPARAMS: return as<ReqPmdPositionLoopParams>(f);
    case MGMSG_MOT_GET_PMDPOSITIONLOOPPARAMS: return as<GetPmdPositionLoopParams>(f);
    case MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS: return as<SetPmdMotorOutputParams>(f);
    case MGMSG_MOT_REQ_PMDMOTOROUTPUTPARAMS: return as<ReqPmdMotorOutputParams>(f);
    case MGMSG_MOT_GET_PMDMOTOROUTPUTPARAMS: return as<GetPmdMotorOutputParams>(f);
    case MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS: return as<SetPmdTrackSettleParams>(f);
    case MGMSG_MOT_REQ_PMDTRACKSETTLEPARAMS: return as<ReqPmdTrackSettleParams>(f);
    case MGMSG_MOT_GET_PMDTRACKSETTLEPARAMS: return as<GetPmdTrackSettleParams>(f);
    case MGMSG_MOT_SET_PMDPROFILEMODEPARAMS: return as<SetPmdProfileModeParams>(f);
    case MGMSG_MOT_REQ_PMDPROFILEMODEPARAMS: return as<ReqPmdProfileModeParams>(f);
    case MGMSG_MOT_GET_PMDPROFILEMODEPARAMS: return as<GetPmdProfileModeParams>(f);
    case MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS: return as<SetPmdCurrentLoopParams>(f);
    case MGMSG_MOT_REQ_PMDCURRENTLOOPPARAMS: return as<ReqPmdCurrentLoopParams>(f);
    case MGMSG_MOT_GET_PMDCURRENTLOOPPARAMS: return as<GetPmdCurrentLoopParams>(f);
    case MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS: return as<SetPmdSettledCurrentLoopParams>(f);
    case MGMSG_MOT_REQ_PMDSETTLEDCURRENTLOOPPARAMS: return as<ReqPmdSettledCurrentLoopParams>(f);
    case MGMSG_MOT_GET_PMDSETTLEDCURRENTLOOPPARAMS: return as<GetPmdSettledCurrentLoopParams>(f);
    case MGMSG_MOT_SET_PMDSTAGEAXISPARAMS: return as<SetPmdStageAxisParams>(f);
    case MGMSG_MOT_REQ_PMDSTAGEAXISPARAMS: return as<ReqPmdStageAxisParams>(f);
    case MGMSG_MOT_GET_PMDSTAGEAXISPARAMS: return as<GetPmdStageAxisParams>(f);
    default:
        return std::nullopt;
    }
}

/// Moves, end-of-move and status messages (p. 41-83).
std::optional<Message> decode_move_status(const Frame& f)
{
    switch (f.id) {
    case MGMSG_MOT_MOVE_HOME: return as<MoveHome>(f);
    case MGMSG_MOT_MOVE_HOMED: return as<MoveHomed>(f);
    case MGMSG_MOT_MOVE_RELATIVE: return as<MoveRelative>(f);
    case MGMSG_MOT_MOVE_ABSOLUTE: return as<MoveAbsolute>(f);
    case MGMSG_MOT_MOVE_JOG: return as<MoveJog>(f);
    case MGMSG_MOT_MOVE_VELOCITY: return as<MoveVelocity>(f);
    case MGMSG_MOT_MOVE_STOP: return as<MoveStop>(f);
    case MGMSG_MOT_MOVE_COMPLETED: return as<MoveCompleted>(f);
    case MGMSG_MOT_MOVE_STOPPED: return as<MoveStopped>(f);
    case MGMSG_MOT_SET_EEPROMPARAMS: return as<SetEepromParams>(f);
    case MGMSG_MOT_REQ_STATUSUPDATE: return as<ReqStatusUpdate>(f);
    case MGMSG_MOT_GET_STATUSUPDATE: return as<GetStatusUpdate>(f);
    case MGMSG_MOT_REQ_DCSTATUSUPDATE: return as<ReqDcStatusUpdate>(f);
    case MGMSG_MOT_GET_DCSTATUSUPDATE: return as<GetDcStatusUpdate>(f);
    case MGMSG_MOT_ACK_DCSTATUSUPDATE: return as<AckDcStatusUpdate>(f);
    case MGMSG_MOT_REQ_STATUSBITS: return as<ReqStatusBits>(f);
    case MGMSG_MOT_GET_STATUSBITS: return as<GetStatusBits>(f);
    case MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS: return as<SuspendEndOfMoveMsgs>(f);
    case MGMSG_MOT_RESUME_ENDOFMOVEMSGS: return as<ResumeEndOfMoveMsgs>(f);
    default:
        return std::nullopt;
    }
}

/// Solenoid Control Messages (p. 84-92).
std::optional<Message> decode_solenoid(const Frame& f)
{
    switch (f.id) {
    case MGMSG_MOT_SET_SOL_OPERATINGMODE: return as<SolSetOperatingMode>(f);
    case MGMSG_MOT_REQ_SOL_OPERATINGMODE: return as<SolReqOperatingMode>(f);
    case MGMSG_MOT_GET_SOL_OPERATINGMODE: return as<SolGetOperatingMode>(f);
    case MGMSG_MOT_SET_SOL_CYCLEPARAMS: return as<SetSolCycleParams>(f);
    case MGMSG_MOT_REQ_SOL_CYCLEPARAMS: return as<ReqSolCycleParams>(f);
    case MGMSG_MOT_GET_SOL_CYCLEPARAMS: return as<GetSolCycleParams>(f);
    case MGMSG_MOT_SET_SOL_INTERLOCKMODE: return as<SolSetInterlockMode>(f);
    case MGMSG_MOT_REQ_SOL_INTERLOCKMODE: return as<SolReqInterlockMode>(f);
    case MGMSG_MOT_GET_SOL_INTERLOCKMODE: return as<SolGetInterlockMode>(f);
    case MGMSG_MOT_SET_SOL_STATE: return as<SolSetState>(f);
    case MGMSG_MOT_REQ_SOL_STATE: return as<SolReqState>(f);
    case MGMSG_MOT_GET_SOL_STATE: return as<SolGetState>(f);
    default:
        return std::nullopt;
    }
}

/// Piezo Control Messages and the TSG001's (p. 93-129).
std::optional<Message> decode_piezo(const Frame& f)
{
    switch (f.id) {
    case MGMSG_PZ_SET_OUTPUTVOLTS: return as<SetPzOutputVolts>(f);
    case MGMSG_PZ_REQ_OUTPUTVOLTS: return as<ReqPzOutputVolts>(f);
    case MGMSG_PZ_GET_OUTPUTVOLTS: return as<GetPzOutputVolts>(f);
    case MGMSG_PZ_SET_OUTPUTPOS: return as<SetPzOutputPos>(f);
    case MGMSG_PZ_REQ_OUTPUTPOS: return as<ReqPzOutputPos>(f);
    case MGMSG_PZ_GET_OUTPUTPOS: return as<GetPzOutputPos>(f);
    case MGMSG_PZ_SET_INPUTVOLTSSRC: return as<SetPzInputVoltsSrc>(f);
    case MGMSG_PZ_REQ_INPUTVOLTSSRC: return as<ReqPzInputVoltsSrc>(f);
    case MGMSG_PZ_GET_INPUTVOLTSSRC: return as<GetPzInputVoltsSrc>(f);
    case MGMSG_PZ_SET_PICONSTS: return as<SetPzPiConsts>(f);
    case MGMSG_PZ_REQ_PICONSTS: return as<ReqPzPiConsts>(f);
    case MGMSG_PZ_GET_PICONSTS: return as<GetPzPiConsts>(f);
    case MGMSG_PZ_SET_OUTPUTLUT: return as<SetPzOutputLut>(f);
    case MGMSG_PZ_REQ_OUTPUTLUT: return as<ReqPzOutputLut>(f);
    case MGMSG_PZ_GET_OUTPUTLUT: return as<GetPzOutputLut>(f);
    case MGMSG_PZ_SET_OUTPUTLUTPARAMS: return as<SetPzOutputLutParams>(f);
    case MGMSG_PZ_REQ_OUTPUTLUTPARAMS: return as<ReqPzOutputLutParams>(f);
    case MGMSG_PZ_GET_OUTPUTLUTPARAMS: return as<GetPzOutputLutParams>(f);
    case MGMSG_PZ_SET_TPZ_DISPSETTINGS: return as<SetTpzDispSettings>(f);
    case MGMSG_PZ_REQ_TPZ_DISPSETTINGS: return as<ReqTpzDispSettings>(f);
    case MGMSG_PZ_GET_TPZ_DISPSETTINGS: return as<GetTpzDispSettings>(f);
    case MGMSG_PZ_SET_TPZ_IOSETTINGS: return as<SetTpzIoSettings>(f);
    case MGMSG_PZ_REQ_TPZ_IOSETTINGS: return as<ReqTpzIoSettings>(f);
    case MGMSG_PZ_GET_TPZ_IOSETTINGS: return as<GetTpzIoSettings>(f);
    case MGMSG_PZ_SET_IOSETTINGS: return as<SetPzIoSettings>(f);
    case MGMSG_PZ_REQ_IOSETTINGS: return as<ReqPzIoSettings>(f);
    case MGMSG_PZ_GET_IOSETTINGS: return as<GetPzIoSettings>(f);
    case MGMSG_PZ_SET_OUTPUTMAXVOLTS: return as<SetPzOutputMaxVolts>(f);
    case MGMSG_PZ_REQ_OUTPUTMAXVOLTS: return as<ReqPzOutputMaxVolts>(f);
    case MGMSG_PZ_GET_OUTPUTMAXVOLTS: return as<GetPzOutputMaxVolts>(f);
    case MGMSG_PZ_SET_TPZ_SLEWRATES: return as<SetTpzSlewRates>(f);
    case MGMSG_PZ_REQ_TPZ_SLEWRATES: return as<ReqTpzSlewRates>(f);
    case MGMSG_PZ_GET_TPZ_SLEWRATES: return as<GetTpzSlewRates>(f);
    case MGMSG_PZ_SET_TSG_IOSETTINGS: return as<SetTsgIoSettings>(f);
    case MGMSG_PZ_REQ_TSG_IOSETTINGS: return as<ReqTsgIoSettings>(f);
    case MGMSG_PZ_GET_TSG_IOSETTINGS: return as<GetTsgIoSettings>(f);
    case MGMSG_PZ_SET_POSCONTROLMODE: return as<PzSetPosControlMode>(f);
    case MGMSG_PZ_REQ_POSCONTROLMODE: return as<PzReqPosControlMode>(f);
    case MGMSG_PZ_GET_POSCONTROLMODE: return as<PzGetPosControlMode>(f);
    case MGMSG_PZ_REQ_PZSTATUSBITS: return as<PzReqPzStatusBits>(f);
    case MGMSG_PZ_ACK_PZSTATUSUPDATE: return as<PzAckPzStatusUpdate>(f);
    case MGMSG_PZ_START_LUTOUTPUT: return as<PzStartLutOutput>(f);
    case MGMSG_PZ_STOP_LUTOUTPUT: return as<PzStopLutOutput>(f);
    case MGMSG_PZ_SET_ZERO: return as<PzSetZero>(f);
    case MGMSG_PZ_REQ_MAXTRAVEL: return as<PzReqMaxTravel>(f);
    case MGMSG_MOT_SET_PZSTAGEPARAMDEFAULTS: return as<MotSetPzStageParamDefaults>(f);
    case MGMSG_PZ_SET_LUTVALUETYPE: return as<PzSetLutValueType>(f);
    case MGMSG_PZ_REQ_TSG_READING: return as<TsgReqReading>(f);
    case MGMSG_PZ_GET_PZSTATUSBITS: return as<PzGetPzStatusBits>(f);
    case MGMSG_PZ_GET_PZSTATUSUPDATE: return as<PzGetPzStatusUpdate>(f);
    case MGMSG_PZ_SET_EEPROMPARAMS: return as<PzSetEepromParams>(f);
    case MGMSG_PZ_GET_MAXTRAVEL: return as<PzGetMaxTravel>(f);
    case MGMSG_PZ_GET_TSG_READING: return as<TsgGetReading>(f);
    default:
        return std::nullopt;
    }
}

} // namespace

Message decode(const Frame& f)
{
    for (auto part : {decode_generic, decode_trio, decode_pmd_trio, decode_move_status, decode_solenoid, decode_piezo})
        if (auto m = part(f))
            return *std::move(m);
    return untyped(f);
}

std::string encode(const Message& m, std::uint8_t dest, std::uint8_t source)
{
    return msg::visit([&](const auto& typed) { return encode(typed, dest, source); }, m);
}

std::uint16_t message_id(const Message& m)
{
    return msg::visit(
        [](const auto& typed) -> std::uint16_t {
            if constexpr (std::is_same_v<std::decay_t<decltype(typed)>, Untyped>)
                return typed.id;
            else
                return std::decay_t<decltype(typed)>::id;
        },
        m);
}

} // namespace rigsim::apt::msg
