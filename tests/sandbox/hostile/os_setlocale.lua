-- expect: os.setlocale is not allowed in the sandbox
os.setlocale("de_DE.UTF-8")  -- would change number formatting for the whole process
