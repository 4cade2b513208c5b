/* The C interface of MESA Imaging's libMesaSR (SwissRanger SR3000/SR4000),
 * declared by keyturn from the library's public documentation (no vendor
 * header is copied). keyturn's driver loads these symbols at run time; the
 * simulator libmesasr-sim exports them with the same behaviour. */
#ifndef KEYTURN_DRIVERS_MESASR_API_H
#define KEYTURN_DRIVERS_MESASR_API_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct CMesaDevice* SRCAM;

enum ModulationFrq {
  MF_40MHz = 0, MF_30MHz, MF_21MHz, MF_20MHz, MF_19MHz, MF_60MHz,
  MF_15MHz, MF_10MHz, MF_29MHz, MF_31MHz, MF_14_5MHz, MF_15_5MHz
};

enum AcquireMode {
  AM_COR_FIX_PTRN = 0x01,
  AM_MEDIAN = 0x04,
  AM_CONV_GRAY = 0x10,
  AM_CONF_MAP = 0x100,
  AM_HW_TRIGGER = 0x200,
  AM_SW_TRIGGER = 0x400,
  AM_DENOISE_ANF = 0x800
};

enum ImgType {
  IT_DISTANCE = 0, IT_AMPLITUDE, IT_INTENSITY, IT_TAP0, IT_TAP1, IT_TAP2, IT_TAP3,
  IT_SUM_DIFF, IT_CONF_MAP, IT_UNDEFINED
};

enum DataType {
  DT_NONE = 0, DT_UCHAR, DT_CHAR, DT_USHORT, DT_SHORT, DT_UINT, DT_INT, DT_FLOAT, DT_DOUBLE
};

typedef struct ImgEntry {
  enum ImgType imgType;
  enum DataType dataType;
  void* data;
  unsigned short width;
  unsigned short height;
} ImgEntry;

enum CallbackMsg {
  CM_MSG_DISPLAY = 0x0001,
  CM_CHANGING = 0x0010,
  CM_CHANGED = 0x0011,
  CM_PROGRESS = 0x0020
};

typedef int SR_FuncCB(SRCAM srCam, unsigned int msg, unsigned int param, void* data);

/* Each function once as a pointer type (for dlsym) and once as a declaration
 * (for the simulator, which defines them). */
#define KEYTURN_MESASR_FUNCTIONS(X)                                                              \
  X(int, SR_OpenUSB, (SRCAM * srCam, unsigned int serialNumber))                                 \
  X(int, SR_OpenETH, (SRCAM * srCam, const char* addr))                                          \
  X(int, SR_OpenDlg, (SRCAM * srCam, int mode, int parent))                                      \
  X(int, SR_Close, (SRCAM srCam))                                                                \
  X(int, SR_Acquire, (SRCAM srCam))                                                              \
  X(void*, SR_GetImage, (SRCAM srCam, unsigned char idx))                                        \
  X(int, SR_GetImageList, (SRCAM srCam, ImgEntry * *imgEntryArray))                              \
  X(unsigned int, SR_GetRows, (SRCAM srCam))                                                     \
  X(unsigned int, SR_GetCols, (SRCAM srCam))                                                     \
  X(int, SR_SetMode, (SRCAM srCam, int mode))                                                    \
  X(int, SR_GetMode, (SRCAM srCam))                                                              \
  X(int, SR_SetIntegrationTime, (SRCAM srCam, unsigned char intTime))                            \
  X(unsigned char, SR_GetIntegrationTime, (SRCAM srCam))                                         \
  X(int, SR_SetModulationFrequency, (SRCAM srCam, enum ModulationFrq modFrq))                    \
  X(enum ModulationFrq, SR_GetModulationFrequency, (SRCAM srCam))                                \
  X(int, SR_SetAmplitudeThreshold, (SRCAM srCam, unsigned short val))                            \
  X(unsigned short, SR_GetAmplitudeThreshold, (SRCAM srCam))                                     \
  X(int, SR_SetAutoExposure, (SRCAM srCam, unsigned char minIntTime, unsigned char maxIntTime,   \
                              unsigned char percentOverPos, unsigned char desiredPos))           \
  X(int, SR_SetDistanceOffset, (SRCAM srCam, unsigned short distOfs))                            \
  X(unsigned short, SR_GetDistanceOffset, (SRCAM srCam))                                         \
  X(void, SR_SetTimeout, (SRCAM srCam, int ms))                                                  \
  X(int, SR_GetDeviceString, (SRCAM srCam, char* buf, int buflen))                               \
  X(unsigned int, SR_ReadSerial, (SRCAM srCam))                                                  \
  X(int, SR_GetVersion, (unsigned short version[4]))                                             \
  X(unsigned char, SR_GetReg, (SRCAM srCam, unsigned char reg))                                  \
  X(int, SR_SetReg, (SRCAM srCam, unsigned char reg, unsigned char val))                         \
  X(SR_FuncCB*, SR_SetCallback, (SR_FuncCB * cb))                                                \
  X(SR_FuncCB*, SR_GetDefaultCallback, (void))                                                   \
  X(int, SR_CoordTrfFlt, (SRCAM srCam, float* x, float* y, float* z, int pitchX, int pitchY,     \
                          int pitchZ))                                                           \
  X(int, SR_CoordTrfDbl, (SRCAM srCam, double* x, double* y, double* z, int pitchX, int pitchY,  \
                          int pitchZ))                                                           \
  X(int, SR_CoordTrfUint16, (SRCAM srCam, short* x, short* y, unsigned short* z, int pitchX,     \
                             int pitchY, int pitchZ))                                            \
  X(int, SR_CoordTrfPntFlt, (SRCAM srCam, const unsigned char* iX, const unsigned char* iY,      \
                             const unsigned short* iDst, float* oX, float* oY, float* oZ,        \
                             int num))                                                           \
  X(int, SR_CoordTrfPntDbl, (SRCAM srCam, const unsigned char* iX, const unsigned char* iY,      \
                             const unsigned short* iDst, double* oX, double* oY, double* oZ,     \
                             int num))                                                           \
  X(int, SR_CoordTrfPntUint16, (SRCAM srCam, const unsigned char* iX, const unsigned char* iY,   \
                                const unsigned short* iDst, short* oX, short* oY,                \
                                unsigned short* oZ, int num))                                    \
  X(int, SR_TCPSend, (SRCAM srCam, void* buf, int len, int flags))                               \
  X(int, SR_TCPRecv, (SRCAM srCam, void* buf, int len, int flags))

#define KEYTURN_MESASR_DECLARE(ret, name, args) ret name args;
KEYTURN_MESASR_FUNCTIONS(KEYTURN_MESASR_DECLARE)
#undef KEYTURN_MESASR_DECLARE

/* keyturn's extension, exported by libmesasr-sim only (MESA's library has no such
 * function; keyturn looks it up with dlsym and uses it when present): opens the
 * simulated camera that the configuration file configPath describes (NULL or "":
 * the simulator's defaults), as SR_OpenUSB(srCam, 0) opens the one that
 * $MESASR_SIM_CONFIG describes. Each camera keeps its own configuration, so one
 * process can open several different simulated cameras without the environment;
 * outside programs (MESA's own test program) keep using $MESASR_SIM_CONFIG.
 * Returns 1 on success, -1 when the configuration or its mesh cannot be read or
 * the camera is unplugged (as SR_OpenUSB). */
typedef int KTSIM_OpenWithConfigFn(SRCAM* srCam, const char* configPath);
KTSIM_OpenWithConfigFn KTSIM_OpenWithConfig;

/* Firmware version register of the SR4000. */
#define SR4000_REG_FIRMWARE 46

#ifdef __cplusplus
}
#endif

#endif /* KEYTURN_DRIVERS_MESASR_API_H */
